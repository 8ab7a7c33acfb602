#!/usr/bin/env bash
# Usage: ci/sweep/slurm-submit.sh [SHARDS] [SWEEP_DIR]
# Builds once, then queues a Slurm array of SHARDS tasks (default 8), each `run --all-corpus
# --shard I/SHARDS`, and a merge job that starts when all of them succeeded.
set -euo pipefail
cd "$(dirname "$0")/../.."
shards=${1:-8}
export SWEEP_SHARDS=$shards SWEEP_DIR=${2:-sweep}
./scripts/build
array=$(sbatch --parsable --export=ALL --array="0-$((shards - 1))" ci/sweep/slurm-shard.sbatch)
merge=$(sbatch --parsable --export=ALL --dependency="afterok:${array}" ci/sweep/slurm-merge.sbatch)
echo "queued shards as job $array and the merge as job $merge; the report will be in $SWEEP_DIR/merged"
