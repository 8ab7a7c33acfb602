#!/usr/bin/env bash
# Usage: ci/sweep/slurm-submit.sh [SHARDS] [SWEEP_DIR] [-- SELECTION...]
# Builds once, then queues a Slurm array of SHARDS tasks (default 8), each shard I of the selection
# (default `run --all-corpus`) into SWEEP_DIR/shard-I (default sweep/), and a merge job that runs
# when all of them have ended (afterany: a cancelled or failed shard is named by the merge, which
# then fails, rather than leaving it pending forever). Job logs go into SWEEP_DIR.
# SWEEP_CPUS_PER_TASK: CPUs per shard (default slurm-shard.sbatch's 8); SUBDIVBENCH_BUILD_DIR: the
# build (default build/).
# Prints the array's and the merge's job ids on its last line: "queued shards as job A and the merge as job M; ...".
set -euo pipefail
cd "$(dirname "$0")/../.."
shards=8 dir=sweep
if [ $# -gt 0 ] && [ "$1" != -- ]; then shards=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" != -- ]; then dir=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" = -- ]; then shift; fi
if ! [[ "$shards" =~ ^[1-9][0-9]{0,3}$ ]]; then echo "slurm-submit: SHARDS must be a whole number from 1, not '$shards'" >&2; exit 2; fi
# The merge reads every shard-I folder: an earlier sweep's results there would be merged as this one's.
if compgen -G "$dir/shard-*" >/dev/null; then
  echo "slurm-submit: $dir holds an earlier sweep's shards: give another SWEEP_DIR, or move it away" >&2
  exit 2
fi
mkdir -p "$dir"
export SWEEP_SHARDS=$shards SWEEP_DIR=$dir
# One binary for every shard: built here, before anything is queued (SWEEP_BUILD=0: the caller
# has built it, as the sweep's test has before ctest runs).
if [ "${SWEEP_BUILD:-1}" != 0 ]; then ./scripts/build; fi
cpus=()
if [ -n "${SWEEP_CPUS_PER_TASK:-}" ]; then cpus=(--cpus-per-task="$SWEEP_CPUS_PER_TASK"); fi
array=$(sbatch --parsable --export=ALL "${cpus[@]}" --output="$dir/slurm-%x-%A_%a.out" --array="0-$((shards - 1))" \
  ci/sweep/slurm-shard.sbatch "$@")
merge=$(sbatch --parsable --export=ALL --output="$dir/slurm-%x-%j.out" --dependency="afterany:${array}" ci/sweep/slurm-merge.sbatch)
echo "queued shards as job $array and the merge as job $merge; the report will be in $dir/merged"
