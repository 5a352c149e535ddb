#!/usr/bin/env bash
# Overload account of the live monitor (issue 19 part 3): plays BAG (sensor_msgs/Imu on /ground/imu) at
# RATE x real time through a monitor with a synthetic catalogue of N two-plane items, records
# /diagnostics and ~overload, lets the node drain its queue after the bag, then prints when overload
# and the ERROR came, the lag, what was shed, and where every sample of the bag went.
#   [RATE=2] [THREADS=1] [START_DELAY=25] [DRAIN=300] bash scripts/measure_overload.sh BAG N
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:$PATH
set +u; source build/devel/setup.bash; set -u
bag=$(realpath "$1"); n=$2
export ROS_HOME=${ROS_HOME:-$(mktemp -d)}
work=$(mktemp -d)
/usr/bin/python3 scripts/make_catalogue.py "$n" "$work/catalogue.yaml"
roslaunch rocking_monitor replay.launch bag:="$bag" catalogue:="$work/catalogue.yaml" start_delay:="${START_DELAY:-25}" \
  rate:="${RATE:-2}" threads:="${THREADS:-1}" > "$work/launch.log" 2>&1 &
launch=$!
until rostopic list >/dev/null 2>&1; do sleep 0.5; done
rosbag record -O "$work/record.bag" /diagnostics /rocking_monitor/overload /clock > /dev/null 2>&1 &
record=$!
# The player ends with the bag; the node then drains its subscriber queue.
player=""
until [ -n "$player" ]; do sleep 0.5; player=$(pgrep -f -- '--clock -d' | head -1 || true); done
while kill -0 "$player" 2>/dev/null; do sleep 1; done
# Drained when the monitor's CPU time stops growing (under 5 % of a core over 2 s; at most DRAIN s).
pid=$(pgrep -f '__name:=rocking_monitor' | head -1)
cpu() { awk '{print $14 + $15}' "/proc/$pid/stat"; }
for ((i = 0; i < ${DRAIN:-300}; i += 2)); do
  a=$(cpu); sleep 2; b=$(cpu)
  [ $((b - a)) -lt $(($(getconf CLK_TCK) / 10)) ] && break
done
# Diagnostics run on /clock, which stopped with the bag: advance it past the end to get the final ones.
end=$(/usr/bin/python3 -c "import rosbag; b=rosbag.Bag('$bag'); print(b.get_end_time())")
for k in 1 2 3; do
  rostopic pub -1 /clock rosgraph_msgs/Clock "clock: {secs: $(/usr/bin/python3 -c "print(int($end) + $k)"), nsecs: 0}" > /dev/null
  sleep 1.5
done
kill -INT $record; wait $record || true
kill -INT $launch; wait $launch || true
/usr/bin/python3 - "$work/record.bag" "$bag" <<'EOF'
import sys, rosbag
rec, played = sys.argv[1], sys.argv[2]
src = rosbag.Bag(played)
start, sent = src.get_start_time(), src.get_message_count()
first_true = error_at = None
clock = 0.0
last = {}
for topic, m, t in rosbag.Bag(rec).read_messages():
    if topic == '/clock':
        clock = m.clock.to_sec()
    if topic == '/rocking_monitor/overload' and m.data and first_true is None:
        first_true = clock  # Bool has no stamp: the /clock last seen
    if topic == '/diagnostics':
        for st in m.status:
            if st.name.startswith('rocking_monitor: sensor') and st.name.endswith('samples'):
                if st.level == 2 and 'overload' in st.message and error_at is None:
                    error_at = m.header.stamp.to_sec()
                last.update({kv.key: kv.value for kv in st.values})
            if st.name == 'rocking_monitor: catalogue':
                last.update({'catalogue ' + kv.key: kv.value for kv in st.values})
f = lambda k: last.get(k, '?')
print('sent %d samples (%.1f s of record)' % (sent, src.get_end_time() - start))
print('overload true at %s s of the bag, diagnostics ERROR (overload) at %s s' % (
    '%.2f' % (first_true - start) if first_true else 'never', '%.2f' % (error_at - start) if error_at else 'never'))
print('received %s, stepped (accepted) %s, lost in transport %s, rejected stamps %s, duplicates %s' % (
    f('received'), f('accepted'), f('lost in transport'), f('rejected implausible stamp'), f('dropped duplicate stamp')))
print('lag max %s s, queue wait max %s s, overload episodes %s, overload now %s' % (
    f('lag, max (s)'), f('backlog, queue wait max (s)'), f('overload episodes'), f('overload')))
print('processing per sample: mean %s s, max %s s' % (f('processing per sample, mean (s)'), f('processing per sample, max (s)')))
shed = {k: v for k, v in last.items() if 'shed' in k}
print('shed: ' + (', '.join('%s = %s' % kv for kv in shed.items()) or 'none reported'))
EOF
[ -n "${KEEP:-}" ] && echo "kept $work" || rm -rf "$work"
