#!/usr/bin/env bash
# The main job on the bundled default (README): installs what is missing, builds, and replays the
# bundled one-sine-pulse bag through the example hospital catalogue with the live monitor, printing a
# per-item table while it rocks and the alarm summary at the end (about 15 s).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
echo "building (log: build/build.log) ..."
mkdir -p build
bash scripts/build.sh >build/build.log 2>&1 || { tail -40 build/build.log; exit 1; }
export PATH=/usr/bin:$PATH
set +u
source build/devel/setup.bash
set -u
export ROS_HOME=${ROS_HOME:-$PWD/build/ros_home}
# The monitor and the bag run under roslaunch in the background (their log: build/demo_launch.log);
# the table runs here and ends by itself 3 s after the last state, so the demo ends with the alarm
# summary and exit status 0 instead of roslaunch's "REQUIRED process has died" banner.
log=build/demo_launch.log
roslaunch rocking_monitor demo.launch table:=false required:=false "$@" >"$log" 2>&1 &
launch_pid=$!
stop_launch() { kill -INT "$launch_pid" 2>/dev/null || true; wait "$launch_pid" 2>/dev/null || true; }
trap stop_launch EXIT
for _ in $(seq 100); do rostopic list >/dev/null 2>&1 && break; sleep 0.2; done
# The dashboard (demo.launch dashboard:=true, the default) sets ~url once its port is bound.
for _ in $(seq 25); do url=$(rosparam get /dashboard/url 2>/dev/null) && break; url=""; sleep 0.2; done
[ -n "$url" ] && echo "Live dashboard: $url (open it in a browser while the pulse plays)"
python3 scripts/monitor_table.py __name:=monitor_table _end_after_idle:=3.0
echo
echo "Monitor log (times since the first sample, and UTC):"
grep -aoE 'rocking_monitor: (BEYOND_TIPPING|COMMITTED|OVERTURNED): .*' "$log" | sed 's/\x1b\[[0-9;]*m//g; s/^/  /' || true
echo "(full log: $log)"
