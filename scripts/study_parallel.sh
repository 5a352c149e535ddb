#!/usr/bin/env bash
# rocking_study split into N shards run by GNU parallel (Debian `parallel`), then merged: the merged
# cases.csv, bodies.csv, records.csv and summary.json results are byte-identical to one run
# (test/tools/study_sharded_byte_identical.sh).
#   scripts/study_parallel.sh N OUT [rocking_study options ...]
# Shards land in OUT/shard<k>, the merge in OUT/all. Environment:
#   ROCKING_STUDY   the binary (default: build/devel/lib/rocking_monitor/rocking_study)
#   PARALLEL_OPTS   options for parallel, e.g. "-j 4", or "--sshloginfile hosts --workdir ." to spread
#                   the shards over machines that see the same paths (default: one job per core)
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 N OUT [rocking_study options ...]" >&2
  exit 2
fi
n=$1
out=$2
shift 2
case "$n" in '' | *[!0-9]* | 0) echo "study_parallel: N must be a positive integer, not '$n'" >&2; exit 2 ;; esac
study=${ROCKING_STUDY:-$(cd "$(dirname "$0")/.." && pwd)/build/devel/lib/rocking_monitor/rocking_study}
mkdir -p "$out"
# -q quotes every argument (options with spaces survive); --halt stops all shards when one fails.
# shellcheck disable=SC2086
parallel -q --halt now,fail=1 ${PARALLEL_OPTS:-} "$study" "$@" --shard "{}/$n" --out "$out/shard{}" --quiet \
  ::: $(seq 1 "$n")
files=()
for k in $(seq 1 "$n"); do files+=("$out/shard$k/cases.csv"); done
"$study" --merge "${files[@]}" --out "$out/all"
