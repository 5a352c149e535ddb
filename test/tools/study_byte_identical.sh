#!/usr/bin/env bash
# rocking_study on a small grid (12 bodies x the Kobe 1995 and Northridge 1994 components, 1800
# cases, with verticals) must write the same bytes as the study did before the layout change
# (test/tools/expected/study_small_grid.sha256, recorded from commit d103a2b), on 1 and 2 threads, on
# the exact path (--exact-trig: glibc sin/cos; the default vector trig meets the accuracy policy of
# rocking_accuracy policy instead of these bytes).
# summary.results is summary.json without its "run" block (paths, threads, wall time).
#   study_byte_identical.sh ROCKING_STUDY RECORDS_DIR EXPECTED_SHA256
set -u
study=$1
records=$2
expected=$3
if [ ! -f "$records/MANIFEST.csv" ]; then
  echo "NOTICE: $records/MANIFEST.csv not found: the byte-identity check needs the shared records; skipped"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for threads in 1 2; do
  out="$tmp/t$threads"
  "$study" --records "$records" --heights 3 --widths 2 --eccentricities 0.5,0.3 --only kobe_1995 --exact-trig \
           --only northridge_1994 --out "$out" --quiet --threads "$threads" >/dev/null || { echo "FAIL: rocking_study exited $?"; exit 1; }
  /usr/bin/python3 -c "import json,sys;d=json.load(open(sys.argv[1]));d.pop('run');print(json.dumps(d,sort_keys=True))" \
      "$out/summary.json" | tr -d '\n' > "$out/summary.results"
  (cd "$out" && sha256sum -c "$expected") || { echo "FAIL: output differs from $expected ($threads threads)"; exit 1; }
done
echo ok
