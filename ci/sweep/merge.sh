#!/usr/bin/env bash
# Merges the shards of a sweep, DIR/shard-I/results.json for I in 0..N-1, into one report in OUT.
# A missing shard (cancelled, crashed, never uploaded) is named on stderr and the merge exits 1;
# the report of the shards that came says which are missing ("Part of a sweep only").
#
#   ci/sweep/merge.sh N DIR OUT [report options, e.g. --allow-mixed]
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ $# -lt 3 ]; then echo "usage: ci/sweep/merge.sh N DIR OUT [report options]" >&2; exit 2; fi
count=$1 dir=$2 out=$3
shift 3
inputs=() missing=()
for ((i = 0; i < count; i++)); do
  if [ -f "$dir/shard-$i/results.json" ]; then inputs+=(--in "$dir/shard-$i/results.json"); else missing+=("$i"); fi
done
if [ ${#inputs[@]} -eq 0 ]; then echo "merge: none of the $count shards has $dir/shard-I/results.json" >&2; exit 2; fi
"${SUBDIVBENCH_BUILD_DIR:-build}/subdivbench" report "${inputs[@]}" --out "$out" "$@"
if [ ${#missing[@]} -gt 0 ]; then
  echo "merge: MISSING shard ${missing[*]} of $count (no $dir/shard-I/results.json): $out/report.html covers part of the sweep" >&2
  exit 1
fi
echo "merge: all $count shards in $out"
