#!/usr/bin/env bash
# Measures the latency from a strong record's data time to the monitor's alarms over SeedLink:
#   [MAX_SAMPLES=n] bash scripts/measure_seedlink_latency.sh
# record_to_mseed writes Rinaldi (Northridge 1994; 318, 228, UP) as 512-byte steim2 miniSEED whose
# data times start a few seconds from now; the test SeedLink server sends each record when its last
# sample's time has come (as a live recorder does); seedlink_bridge -> monitor (the items of
# test/ros/seedlink_monitor.yaml). Prints, per alarm, wall time of receipt - data time of the event,
# and the bridge's sample latency from /diagnostics. MAX_SAMPLES caps the samples per record
# (a recorder configured for short records). Needs a build (scripts/build.sh) and the records.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:$PATH
set +u; source build/devel/setup.bash; set -u
records=${RECORDS:-../shared/records}/northridge_1994
tools=build/devel/lib/rocking_monitor
port=18571
tmp=$(mktemp -d)
# The run's own ROS home (journal, snapshot, logs) unless given: a journal kept across runs is read
# whole at every start.
export ROS_MASTER_URI=http://localhost:11471 ROS_HOME=${ROS_HOME:-$tmp/ros_home}
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; rm -rf "$tmp"; }
trap cleanup EXIT
roscore -p 11471 >"$tmp/roscore.log" 2>&1 & pids+=($!)
sleep 3
start=$(( $(date +%s) + 10 ))
extra=(); [ -n "${MAX_SAMPLES:-}" ] && extra=(--max-samples "$MAX_SAMPLES")
"$tools/record_to_mseed" --file "$records/Rinaldi318.AT2" --file "$records/Rinaldi228.AT2" --file "$records/RinaldiUP.AT2" \
  -o "$tmp/rin.mseed" --gain 427000 --network CI --station RIN --orientation 12 --start-time "$start" "${extra[@]}"
/usr/bin/python3 test/ros/seedlink_test_server.py --port $port --realtime --clock-file "$tmp/clock" "$tmp/rin.mseed" \
  >"$tmp/server.log" 2>&1 & pids+=($!)
"$tools/seedlink_bridge" __name:=seedlink_bridge _server:=localhost:$port _streams:=CI_RIN:HN? _gain:=427000 _azimuth:=318 \
  _frame_id:=accelerometer >"$tmp/bridge.log" 2>&1 & pids+=($!)
rosparam load config/monitor.yaml /rocking_monitor
rosparam load test/ros/seedlink_monitor.yaml /rocking_monitor
"$tools/monitor" __name:=rocking_monitor _gravity_baseline/mode:=fixed _publish_markers:=false >"$tmp/monitor.log" 2>&1 & pids+=($!)
# Listen until the record (20 s) is over, then report.
/usr/bin/python3 - "$start" <<'PY'
import sys, time, rospy
from rocking_monitor.msg import OverturnAlarm
from diagnostic_msgs.msg import DiagnosticArray
start = float(sys.argv[1])
names = {2: 'beyond_tipping', 3: 'committed', 4: 'overturned'}
rows, lat = [], {}
def on_alarm(m):
    rows.append((time.time() - m.event_time, m.item_id, names.get(m.level, m.level), m.event_time - start))
def on_diag(d):
    for s in d.status:
        if s.name.endswith('seedlink station CI_RIN'):
            for kv in s.values:
                if kv.key.startswith('latency'):
                    lat.setdefault(kv.key, []).append(float(kv.value))
rospy.init_node('latency_listener')
rospy.Subscriber('/rocking_monitor/alarms', OverturnAlarm, on_alarm, queue_size=1000)
rospy.Subscriber('/diagnostics', DiagnosticArray, on_diag, queue_size=100)
while not rospy.is_shutdown() and time.time() < start + 24:
    time.sleep(0.1)
print('%-16s %-15s %12s %12s' % ('item', 'level', 'event (s)', 'latency (s)'))
for l, item, level, t in sorted(rows, key=lambda r: r[3]):
    print('%-16s %-15s %12.3f %12.3f' % (item, level, t, l))
if rows:
    ls = sorted(r[0] for r in rows)
    print('alarms: %d, latency min %.3f s, median %.3f s, max %.3f s' % (len(ls), ls[0], ls[len(ls) // 2], ls[-1]))
mins = [v for v in lat.get('latency min since last report (s)', []) if v > 0]
maxs = lat.get('latency max since last report (s)', [])
if mins and maxs:
    print('bridge: sample latency (data time -> publication) from %.3f s (newest sample of a record) to %.3f s (oldest)' % (min(mins), max(maxs)))
PY
grep -h "records of" "$tmp"/*.log 2>/dev/null | head -1 || true
