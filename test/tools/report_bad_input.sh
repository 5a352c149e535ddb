#!/usr/bin/env bash
# rocking_report on bad input: exit status 2 and exactly one line on stderr naming the file and the fault.
# $1 = the rocking_report script, $2 = the source tree (for the bundled bag without the monitor's topics).
set -u
tool=$1 src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
check() {  # check NAME EXPECTED_SUBSTRING ARGS...
  local name=$1 want=$2; shift 2
  /usr/bin/python3 "$tool" "$@" >"$tmp/out" 2>"$tmp/err"; local rc=$?
  local lines; lines=$(wc -l <"$tmp/err")
  if [[ $rc -ne 2 || $lines -ne 1 ]] || ! grep -q "^rocking_report: error: .*$want" "$tmp/err"; then
    echo "FAIL $name: exit $rc, $lines stderr lines (want 2, 1, '$want'):"; cat "$tmp/err"; fail=1
  else
    echo "ok   $name: $(cat "$tmp/err")"
  fi
  if ls "$tmp"/*.html >/dev/null 2>&1; then echo "FAIL $name: wrote a report"; fail=1; fi
}
check "bag without the monitor's topics" "synthetic_one_sine_pulse.bag: no monitor topics" \
      "$src/bags/synthetic_one_sine_pulse.bag" -o "$tmp/r.html"
check "missing bag" "$tmp/missing.bag: no such file" "$tmp/missing.bag" -o "$tmp/r.html"
check "not a bag" "one_sine_pulse.csv: not a readable bag" "$src/bags/one_sine_pulse.csv" -o "$tmp/r.html"
check "no arguments" "the following arguments are required: bag"
check "unknown flag" "unrecognized arguments: --frobnicate" "$src/bags/synthetic_one_sine_pulse.bag" --frobnicate
exit $fail
