#!/bin/bash
# A tool's --help is byte for byte test/tools/expected/<tool>.help (issue 53: the mains became parse
# + run; users and scripts read --help, so a refactor must not change it, and a new flag shows up
# here as a one-line diff to review). The tool runs by its bare name from PATH, so CLI11's "Usage:"
# line is the same from any build directory, with ROCKING_RECORDS_DIR unset (rocking_accuracy reads
# it); the compiled-in records directory (the --records default) is compared as @ROCKING_RECORDS_DIR@.
#   help_unchanged.sh TOOL_EXE EXPECTED RECORDS_DIR
set -u
exe=$1 expected=$2 records=$3
tool=$(basename "$exe")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
env -u ROCKING_RECORDS_DIR PATH="$(dirname "$exe"):$PATH" "$tool" --help > "$tmp/help.raw" 2>&1 ||
  { echo "FAIL: $tool --help exited $?"; cat "$tmp/help.raw"; exit 1; }
# literal replacement (the path may hold regex characters)
/usr/bin/python3 -c 'import sys; t=open(sys.argv[1]).read(); sys.stdout.write(t.replace(sys.argv[2], "@ROCKING_RECORDS_DIR@"))' \
  "$tmp/help.raw" "$records" > "$tmp/help.txt"
if ! diff -u "$expected" "$tmp/help.txt"; then
  echo "FAIL: $tool --help differs from $expected (lines with - are expected, + are printed now)"
  exit 1
fi
echo "ok: $tool --help is $(wc -l < "$expected") lines as expected"
