#!/usr/bin/env bash
# One shard of a sweep: shard I of N of a selection into OUT, results.json only (the merge writes
# the report). slurm-shard.sbatch and the GitHub workflow's shard job both run it.
#
#   ci/sweep/shard.sh I N OUT [SELECTION...]
#
# SELECTION: `run`'s selection options, one argument each (default --all-corpus); without any,
# $SUBDIVBENCH_SWEEP_SELECTION_FILE (one argument a line) gives them, so that the workflow's
# steps run unchanged on a small selection (ci/sweep/run-workflow-locally). Arguments are passed
# as an argument vector, never through a shell.
# Exit 0, or 1 when a row failed its checks (its results are complete and merge); anything worse
# (no results.json written) is 2 or run's own code.
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ $# -lt 3 ]; then echo "usage: ci/sweep/shard.sh I N OUT [SELECTION...]" >&2; exit 2; fi
index=$1 count=$2 out=$3
shift 3
selection=("$@")
if [ ${#selection[@]} -eq 0 ] && [ -n "${SUBDIVBENCH_SWEEP_SELECTION_FILE:-}" ]; then
  mapfile -t selection < "$SUBDIVBENCH_SWEEP_SELECTION_FILE"
fi
[ ${#selection[@]} -gt 0 ] || selection=(--all-corpus)
status=0
"${SUBDIVBENCH_BUILD_DIR:-build}/subdivbench" run "${selection[@]}" --shard "$index/$count" --out "$out" --no-report || status=$?
echo "shard $index/$count: exit code $status"
if [ "$status" -gt 1 ] || [ ! -f "$out/results.json" ]; then exit "$((status > 1 ? status : 2))"; fi
