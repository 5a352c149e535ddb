#!/usr/bin/env bash
# Measures the dashboard under load: a catalogue of N items (scripts/make_catalogue.py), BAG replayed at
# real time through the monitor, the dashboard, and one live page in headless Chromium (event stream,
# real time, not virtual). Prints the page's time per state delta (its handler: rows and state) and per
# frame drawn (plan, side view, charts), from the page's own performance.now() hooks, and the
# dashboard's CPU over the run (/proc utime + stime).
#   bash scripts/measure_dashboard_load.sh BAG [N ...]      (default N: 10000)
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:$PATH
set +u; source build/devel/setup.bash; set -u
bag=$(realpath "$1"); shift
counts=("$@"); [ ${#counts[@]} -gt 0 ] || counts=(10000)
fixed_home=${ROS_HOME:-}  # else a fresh ROS home per run: the monitor and the dashboard read the whole journal
export ROS_MASTER_URI=http://localhost:${MASTER_PORT:-11397}
port=${DASHBOARD_PORT:-18399}
devtools=${DEVTOOLS_PORT:-19399}
delay=${START_DELAY:-20}   # s before the bag plays: the page loads the snapshot first
duration=$(/usr/bin/python3 -c "import rosbag,sys; b=rosbag.Bag(sys.argv[1]); print(int(b.get_end_time()-b.get_start_time()+1))" "$bag")
tick=$(getconf CLK_TCK)
printf "%7s %8s %11s %11s %11s %10s %10s %10s %12s %12s\n" items deltas "delta mean" "delta p95" "delta max" "frames" "draw mean" "draw max" "max changed" "dashboard CPU"
for n in "${counts[@]}"; do
  cat=$(mktemp --suffix=.yaml); log=$(mktemp); dom=$(mktemp); profile=$(mktemp -d)
  home=$(mktemp -d); export ROS_HOME=${fixed_home:-$home}
  /usr/bin/python3 scripts/make_catalogue.py "$n" "$cat"
  roslaunch -p "${ROS_MASTER_URI##*:}" rocking_monitor replay.launch bag:="$bag" catalogue:="$cat" required:=true \
    start_delay:="$delay" > "$log" 2>&1 &
  launch=$!
  for _ in $(seq 240); do rosparam get /rocking_monitor/sensors >/dev/null 2>&1 && break; sleep 0.5; done
  build/devel/lib/rocking_monitor/dashboard _port:="$port" _monitor:=/rocking_monitor >> "$log" 2>&1 &
  dash=$!
  for _ in $(seq 300); do curl -s -o /dev/null "http://127.0.0.1:$port/" && break; sleep 0.2; done
  cpu0=$(awk '{print $14 + $15}' /proc/$dash/stat); t0=$(date +%s.%N)
  # One live page (event stream, real time) through the replay and 4 s after it; its timing summary is
  # read from its title on Chromium's DevTools endpoint.
  chromium --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking \
    --user-data-dir="$profile" --window-size=1400,1000 --remote-debugging-port="$devtools" \
    "http://127.0.0.1:$port/?measure=1" > /dev/null 2>&1 &
  browser=$!
  sleep $(( delay + duration + 4 ))
  curl -s "http://127.0.0.1:$devtools/json/list" > "$dom" || true
  cpu1=$(awk '{print $14 + $15}' /proc/$dash/stat); t1=$(date +%s.%N)
  kill $browser 2>/dev/null || true; wait $browser 2>/dev/null || true
  kill -INT $dash 2>/dev/null || true; wait $dash 2>/dev/null || true
  kill -INT $launch 2>/dev/null || true; wait $launch 2>/dev/null || true
  get() { /usr/bin/python3 -c "import html,json,sys; t=[p['title'] for p in json.load(open(sys.argv[1])) if p['title'].startswith('measure ')]; print(json.loads(html.unescape(t[0][8:])).get(sys.argv[2], '?') if t else '?')" "$dom" "$1"; }
  /usr/bin/python3 -c "import sys; a=sys.argv; print('%7s %8s %11s %11s %11s %10s %10s %10s %12s %11.1f %%' % (a[1], a[2], a[3]+' ms', a[4]+' ms', a[5]+' ms', a[6], a[7]+' ms', a[8]+' ms', a[9], 100.0*(float(a[10])-float(a[11]))/float(a[12])/(float(a[13])-float(a[14]))))" \
    "$n" "$(get deltaCount)" "$(get deltaMeanMs)" "$(get deltaP95Ms)" "$(get deltaMaxMs)" "$(get drawCount)" \
    "$(get drawMeanMs)" "$(get drawMaxMs)" "$(get deltaItemsMax)" "$cpu1" "$cpu0" "$tick" "$t1" "$t0"
  [ -n "${KEEP:-}" ] && echo "kept: $log $dom" || rm -rf "$cat" "$log" "$dom" "$profile" "$home"
done
