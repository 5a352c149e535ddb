#!/usr/bin/env bash
# Post-event report from record files and a catalogue, when there is no bag of the event: the record
# becomes an Imu bag (record_to_bag), which is replayed through the monitor and the report node
# (replay.launch report_dir:=...) exactly as a live event would be; the report is the HTML the node
# writes when the event ends.
#
#   scripts/report_from_record.sh --catalogue CAT.yaml --out DIR [--rate R] -- RECORD_TO_BAG_ARGS...
#   e.g. scripts/report_from_record.sh --catalogue config/catalogue_example.yaml --out reports -- \
#          --file ../shared/records/northridge_1994/Rinaldi318.AT2 --file .../Rinaldi228.AT2 --file .../RinaldiUP.AT2
#
# --rate: replay speed (default 1: real time; a few times faster is fine for small catalogues, the
# report's health section shows any sample the monitor could not keep up with).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
export PATH=/usr/bin:$PATH
catalogue="" out="" rate=1
while [ $# -gt 0 ]; do
  case "$1" in
    --catalogue) catalogue="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --rate) rate="$2"; shift 2 ;;
    --) shift; break ;;
    *) echo "report_from_record: error: unknown option '$1' (usage: --catalogue F --out DIR [--rate R] -- record_to_bag args)" >&2; exit 2 ;;
  esac
done
[ -n "$catalogue" ] && [ -n "$out" ] && [ $# -gt 0 ] || {
  echo "report_from_record: error: need --catalogue FILE, --out DIR and record_to_bag arguments after --" >&2; exit 2; }
[ -f "$catalogue" ] || { echo "report_from_record: error: $catalogue: no such file" >&2; exit 2; }
catalogue="$(cd "$(dirname "$catalogue")" && pwd)/$(basename "$catalogue")"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
# The package's environment: an installed or a built (devel) workspace.
if ! command -v rospack >/dev/null || ! rospack find rocking_monitor >/dev/null 2>&1; then
  for setup in "$here/build/devel/setup.bash" "$here/devel/setup.bash"; do
    # shellcheck disable=SC1090
    [ -f "$setup" ] && { set +u; source "$setup"; set -u; break; }
  done
fi
tools="$(dirname "$(command -v record_to_bag 2>/dev/null || echo "$here/build/devel/lib/rocking_monitor/record_to_bag")")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$tools/record_to_bag" "$@" -o "$work/event.bag" >&2 || { echo "report_from_record: error: record_to_bag failed" >&2; exit 2; }
reports() { find "$out" -maxdepth 1 -name '*.html' | wc -l; }
before=$(reports)
# Own master on a free port: never disturbs a running ROS system.
# The OS picks the port (a random one collided with the other masters of a parallel ctest, issue 42).
port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://127.0.0.1:$port" ROS_HOME="$work/ros"
roslaunch -p "$port" rocking_monitor replay.launch bag:="$work/event.bag" catalogue:="$catalogue" \
  report_dir:="$out" rate:="$rate" required:=false >"$work/launch.log" 2>&1 &
launch=$!
# The report node writes when the event has ended (all items still or input stopped, docs/report.md).
duration=$(rosbag info -y -k duration "$work/event.bag" 2>/dev/null || echo 600)
deadline=$(( $(date +%s) + $(awk -v d="$duration" -v r="$rate" 'BEGIN { printf "%d", d / r }') + 90 ))
while [ "$(reports)" -le "$before" ]; do
  if ! kill -0 "$launch" 2>/dev/null || [ "$(date +%s)" -gt "$deadline" ]; then
    kill -INT "$launch" 2>/dev/null || true; wait "$launch" 2>/dev/null || true
    echo "report_from_record: error: no report was written (launch log below)" >&2; tail -20 "$work/launch.log" >&2; exit 1
  fi
  sleep 1
done
sleep 2  # the node writes the bag, then the page
kill -INT "$launch" 2>/dev/null || true
wait "$launch" 2>/dev/null || true
find "$out" -maxdepth 1 -name '*.html' -newer "$work/event.bag" -print
