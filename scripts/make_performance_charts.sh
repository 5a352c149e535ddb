#!/usr/bin/env bash
# Regenerates the performance study (docs/performance.md, issue 6) on this machine:
#   1. builds rocking_benchmarks and rocking_accuracy (Release) in build-bench/,
#   2. runs the Google benchmarks (ns per item-step, real-time capacity at 200 Hz) -> JSON,
#   3. runs the accuracy driver (work-precision, overturn agreement over every .AT2 record,
#      stability maps) -> CSV; work-precision also runs the batch engine (BatchRocking) and fails,
#      stopping this script, if its exact-trig lanes are not the scalar model's bits,
#   4. draws the charts (PNG + SVG) and docs/performance/summary.md.
# Raw data stays in build-bench/performance/ (large, regenerable); charts go to docs/performance/.
#
#   bash scripts/make_performance_charts.sh [--quick] [--no-bench] [--no-accuracy]
#
# --quick: fewer cases and short benchmark runs (a smoke test, about 1 minute; not for the docs).
# Uses at most 2 cores (-j2, --jobs 2). Records are read from ../shared/records (or
# ROCKING_RECORDS_DIR); without them the record cases are skipped with a notice.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:$PATH
BUILD=${BUILD_DIR:-build-bench}
DATA="$BUILD/performance"
OUT=docs/performance
quick=0; bench=1; accuracy=1
for a in "$@"; do
  case "$a" in
    --quick) quick=1 ;;
    --no-bench) bench=0 ;;
    --no-accuracy) accuracy=0 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "make_performance_charts: unknown option $a" >&2; exit 2 ;;
  esac
done

cmake -S . -B "$BUILD" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j2 --target rocking_accuracy rocking_benchmarks
BIN="$BUILD/devel/lib/rocking_monitor"
[ -x "$BIN/rocking_accuracy" ] || BIN="$BUILD/bin"   # without catkin
mkdir -p "$DATA" "$OUT"

if [ "$bench" = 1 ]; then
  echo "== benchmarks (Google Benchmark; a few minutes)"
  extra=()
  if [ "$quick" = 1 ]; then extra=(--benchmark_filter='item/(free|pulse)/.*(tol:1e-08|substeps:4|analytic)|catalogue/free' --benchmark_min_time=0.05); fi
  "$BIN/rocking_benchmarks" --benchmark_out="$DATA/benchmarks.json" --benchmark_out_format=json \
      --benchmark_counters_tabular=true "${extra[@]}" | tee "$DATA/benchmarks.txt"
fi
if [ "$accuracy" = 1 ]; then
  echo "== accuracy, overturn agreement and stability maps"
  q=(); [ "$quick" = 1 ] && q=(--quick)
  "$BIN/rocking_accuracy" --out "$DATA" --jobs 2 "${q[@]}"
fi
echo "== charts"
/usr/bin/python3 scripts/plot_performance.py --data "$DATA" --out "$OUT"
echo "charts and summary in $OUT/ (raw data in $DATA/)"
