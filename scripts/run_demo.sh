#!/usr/bin/env bash
# The main job on the bundled default (README): installs what is missing, builds, and runs
# rocking_sim for three free-standing items under the bundled one-sine pulse.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh >build.log 2>&1 || { cat build.log; exit 1; }
sim=build/devel/lib/rocking_monitor/rocking_sim
[ -x "$sim" ] || sim=build/bin/rocking_sim
record=bags/one_sine_pulse.csv
echo
echo "Bundled record: $record ($(grep -m1 '^#' $record | sed 's/^# //'))"
run() {
  echo
  echo "== $1"
  shift
  "$sim" --record "$record" "$@"
}
run "museum vase, slender and symmetric (B 0.15 m, h 0.35 m)" --width 0.15 --cg-height 0.35
run "shelving unit, eccentric load (B 0.30 m, h 0.90 m, nu1 0.3)" --width 0.30 --cg-height 0.90 --eccentricity 0.3 --mu-s 0.6
run "medicine cabinet, stocky (B 0.50 m, h 0.90 m, nu1 0.4)" --width 0.50 --cg-height 0.90 --eccentricity 0.4 --mu-s 0.6
