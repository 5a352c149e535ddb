#!/usr/bin/env bash
# Measures the live monitor's processing time per input sample for catalogues of N items:
#   [THREADS=k] [FIDELITY=adaptive|rocking|contact] [PLANES=2|1] [UNCERTAIN=0|1] [SOLID=0|1] [RATE=r] [START_DELAY=s] [SUBSCRIBE=0|1] bash scripts/measure_monitor_load.sh BAG [N ...]
#   (default N: 1 100 10000)
# Replays BAG (sensor_msgs/Imu on /ground/imu) at real time through a monitor fed by a synthetic
# catalogue of N items (two rocking planes each; PLANES=1: no depth; UNCERTAIN=1: ensembles of
# ~ensemble_size members per item) and prints the mean and max processing time per sample from /diagnostics;
# RATE=2 plays the bag at twice real time. Then one line of overload figures (issue 19): lag, queue wait,
# ~overload, samples stepped and lost in transport, publications shed.
# SUBSCRIBE=1: a subscriber (topic_tools relay, C++, no deserialization) on ~states, ~state_changes,
# ~markers and /tf, so that the monitor fills and serializes them (it skips a topic nobody reads).
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:$PATH
set +u; source build/devel/setup.bash; set -u
bag=$(realpath "$1"); shift
counts=("$@"); [ ${#counts[@]} -gt 0 ] || counts=(1 100 10000)
# A fresh ROS home per run unless ROS_HOME is given: the monitor reads its whole alarm journal and its
# state snapshot at start, and one shared across runs grows by ~10 MB a run (10,000 items on
# Takatori): 40 runs made a 430 MB journal whose reading overlapped the replay and doubled the lag.
fixed_home=${ROS_HOME:-}
printf "%8s %14s %14s %10s %16s %16s\n" items "mean (ms)" "max (ms)" "samples" "states (ms)" "markers+tf (ms)"
for n in "${counts[@]}"; do
  home=${fixed_home:-$(mktemp -d)}
  export ROS_HOME=$home
  cat=$(mktemp --suffix=.yaml)
  single=(); [ "${PLANES:-2}" = 1 ] && single=(--single-plane)
  [ "${UNCERTAIN:-0}" = 1 ] && single+=(--uncertain)
  [ "${SOLID:-0}" = 1 ] && single+=(--solid)  # with solid_model 3d: every item runs the 3-D model
  /usr/bin/python3 scripts/make_catalogue.py "$n" "$cat" "${single[@]}"
  log=$(mktemp)
  roslaunch rocking_monitor replay.launch bag:="$bag" catalogue:="$cat" required:=true start_delay:="${START_DELAY:-3}" rate:="${RATE:-1}" threads:="${THREADS:-1}" fidelity:="${FIDELITY:-adaptive}" solid_model:="$([ "${SOLID:-0}" = 1 ] && echo 3d || echo auto)" \
    > "$log" 2>&1 &
  pid=$!
  relays=()
  if [ "${SUBSCRIBE:-0}" = 1 ]; then
    for t in /rocking_monitor/states /rocking_monitor/state_changes /rocking_monitor/markers /tf; do
      rosrun topic_tools relay "$t" "/load_sink$t" __name:="load_sink_$(basename "$t")" >/dev/null 2>&1 &
      relays+=($!)
    done
  fi
  # One subscriber on /diagnostics for the whole run, until the bag is over (the launch ends with
  # it). Not a new `rostopic echo -n 1` every few seconds: each costs ~0.5 s of CPU (Python start-up),
  # ~18 % of a core taken from the monitor on a 2-core machine.
  diaglog=$(mktemp)
  until rostopic list >/dev/null 2>&1 || ! kill -0 $pid 2>/dev/null; do sleep 0.5; done  # the master is up
  PYTHONUNBUFFERED=1 rostopic echo /diagnostics > "$diaglog" 2>/dev/null &
  echo_pid=$!
  while kill -0 $pid 2>/dev/null; do sleep 1; done
  kill "$echo_pid" 2>/dev/null || true
  wait "$echo_pid" 2>/dev/null || true
  # The last message with the monitor's sample statistics.
  diag=$(awk 'BEGIN{RS="\n---\n"} /processing per sample, mean/ {last=$0} END{print last}' "$diaglog")
  rm -f "$diaglog"
  mean=$(echo "$diag" | grep -A1 'processing per sample, mean' | sed -n 's/.*value: "\(.*\)"/\1/p' | head -1)
  max=$(echo "$diag" | grep -A1 'processing per sample, max' | sed -n 's/.*value: "\(.*\)"/\1/p' | head -1)
  samples=$(echo "$diag" | grep -A1 '"accepted"' | sed -n 's/.*value: "\(.*\)"/\1/p' | head -1)
  states=$(echo "$diag" | grep -A1 'states publication, mean' | sed -n 's/.*value: "\(.*\)"/\1/p' | head -1)
  markers=$(echo "$diag" | grep -A1 'markers and tf publication, mean' | sed -n 's/.*value: "\(.*\)"/\1/p' | head -1)
  /usr/bin/python3 -c "import sys; print('%8d %14.4f %14.4f %10s %16.3f %16.3f' % (int(sys.argv[1]), float(sys.argv[2])*1e3, float(sys.argv[3])*1e3, sys.argv[4], float(sys.argv[5])*1e3, float(sys.argv[6])*1e3))" \
    "$n" "${mean:-nan}" "${max:-nan}" "${samples:-?}" "${states:-nan}" "${markers:-nan}"
  field() { echo "$diag" | grep -A1 "key: \"$1\"" | sed -n 's/.*value: "\(.*\)"/\1/p' | head -1; }
  echo "         overload: $(field overload) (episodes $(field 'overload episodes')), lag max $(field 'lag, max (s)') s," \
       "queue wait max $(field 'backlog, queue wait max (s)') s, received $(field received), lost in transport" \
       "$(field 'lost in transport'), shed: $(field 'markers and tf publications shed (overload)') markers+tf," \
       "$(field 'states publications shed (overload)') states; published: $(field 'states publications') states," \
       "$(field 'markers and tf publications') markers+tf"
  grep -m1 "overload:" "$log" || true
  for r in "${relays[@]}"; do kill "$r" 2>/dev/null || true; done
  rm -f "$cat" "$log"
  [ -n "$fixed_home" ] || rm -rf "$home"
done
