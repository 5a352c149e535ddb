#!/usr/bin/env bash
# An unknown flag gets one line "<program>: error: ..." on stderr and a non-zero exit status.
#   unknown_flag.sh PROGRAM EXECUTABLE
set -u
program=$1
exe=$2
out=$("$exe" --no-such-flag 2>&1 </dev/null)
status=$?
lines=$(printf '%s\n' "$out" | wc -l)
echo "exit status $status, output: $out"
[ "$status" -ne 0 ] || { echo "FAIL: exit status 0"; exit 1; }
[ "$lines" -eq 1 ] || { echo "FAIL: $lines lines, expected 1"; exit 1; }
case "$out" in
  "$program: error: "*--no-such-flag*) echo "ok" ;;
  *) echo "FAIL: not prefixed '$program: error: ' or does not name the flag"; exit 1 ;;
esac
