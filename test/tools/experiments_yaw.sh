#!/bin/bash
# rocking_experiments: a specimen's yaw on the table (catalogue `pose: {yaw}`) is the same rotation as
# --table-azimuth with the opposite sign (the node rotates a sensor's input into the item's frame the
# same way), so the two runs' tables are identical; the azimuth changes the answer (else the test
# proves nothing); a yaw on a planar run and a tilted pose are refused naming the item.
# Exit 77 (skipped) when the data is absent.
set -u
exe=$1 dir=$2 catalogue=$3
if [ ! -f "$dir/outcomes.csv" ]; then echo "SKIP: $dir not found (shaking-table tests skipped)"; exit 77; fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
n=12
"$exe" "$dir" --catalogue "$catalogue" --max-tests $n --table-azimuth -5 --out "$tmp/flag.csv" > /dev/null ||
  { echo "FAIL: --table-azimuth run"; exit 1; }
sed 's/^  - id: \(.*\)$/  - id: \1\n    pose: {parent_frame: table, yaw: 0.087266462599716474}/' "$catalogue" > "$tmp/yaw.yaml"
grep -c "yaw:" "$tmp/yaw.yaml" | grep -q '^[1-9]' || { echo "FAIL: no pose written"; exit 1; }
"$exe" "$dir" --catalogue "$tmp/yaw.yaml" --max-tests $n --out "$tmp/pose.csv" > /dev/null ||
  { echo "FAIL: pose run"; exit 1; }
"$exe" "$dir" --catalogue "$catalogue" --max-tests $n --out "$tmp/none.csv" > /dev/null ||
  { echo "FAIL: plain run"; exit 1; }
cmp -s "$tmp/flag.csv" "$tmp/pose.csv" || { echo "FAIL: pose yaw +5 deg != --table-azimuth -5"; diff "$tmp/flag.csv" "$tmp/pose.csv" | head; fail=1; }
cmp -s "$tmp/flag.csv" "$tmp/none.csv" && { echo "FAIL: the azimuth changed nothing in $n tests"; fail=1; }
# yaw and the flag add up: pose +5 deg with --table-azimuth +5 is the plain run
"$exe" "$dir" --catalogue "$tmp/yaw.yaml" --max-tests $n --table-azimuth 5 --out "$tmp/sum.csv" > /dev/null ||
  { echo "FAIL: pose + flag run"; exit 1; }
cmp -s "$tmp/sum.csv" "$tmp/none.csv" || { echo "FAIL: pose +5 deg with --table-azimuth +5 != no rotation"; fail=1; }
if "$exe" "$dir" --catalogue "$tmp/yaw.yaml" --max-tests 1 --model planar > "$tmp/err.txt" 2>&1; then
  echo "FAIL: a yaw on a planar run was accepted"; fail=1
fi
grep -q "item 'SP1': pose.yaw needs the 3-D model" "$tmp/err.txt" || { echo "FAIL: planar yaw error: $(cat "$tmp/err.txt")"; fail=1; }
sed 's/yaw: 0.0872/roll: 0.1, yaw: 0.0872/' "$tmp/yaw.yaml" > "$tmp/roll.yaml"
if "$exe" "$dir" --catalogue "$tmp/roll.yaml" --max-tests 1 > "$tmp/err.txt" 2>&1; then
  echo "FAIL: a rolled specimen was accepted"; fail=1
fi
grep -q "item 'SP1': pose: a specimen stands on the table" "$tmp/err.txt" || { echo "FAIL: roll error: $(cat "$tmp/err.txt")"; fail=1; }
[ $fail -eq 0 ] && echo "PASS: pose yaw == -table azimuth on $n tests, refusals name the item"
exit $fail
