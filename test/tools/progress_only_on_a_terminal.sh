#!/bin/bash
# The long tools' progress (issue 53, src/tools/progress_meter.*) is drawn only when stderr is a
# terminal and not with --quiet: a log, a pipe or ctest gets no progress text, and stdout is the same
# with or without it. The terminal is a pseudo-terminal from script(1) (util-linux); what the tools
# write there is checked for the done/total of the run, not for any rate or time.
#   progress_only_on_a_terminal.sh BIN_DIR EXPERIMENTS_DIR CATALOGUE RECORDS_DIR
# Exit 77 (skipped) without the shared shaking-table tests or records.
set -u
bin=$1 experiments=$2 catalogue=$3 records=$4
if [ ! -f "$experiments/outcomes.csv" ] || [ ! -d "$records/kobe_1995" ]; then
  echo "SKIP: $experiments or $records not found"; exit 77
fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
# one record for rocking_accuracy's overturn part (it runs every .AT2 below --records)
mkdir -p "$tmp/one_record" && ln -s "$records/kobe_1995/RSN1120_KOBE_TAK000.AT2" "$tmp/one_record/"

# name  command (stdout goes to $tmp/name.*.out)  what a terminal shows at the end
runs=(
  "experiments|$bin/rocking_experiments $experiments --catalogue $catalogue --max-tests 3|3/3 tests"
  "margins|$bin/rocking_experiments $experiments --catalogue $catalogue --max-tests 2 --margins $tmp/m.csv --margin-grid 3 --margin-bisections 1|2/2 tests"
  "study|$bin/rocking_study --records $records --only kobe_1995 --heights 1 --widths 2 --eccentricities 0.5 --threads 1 --out $tmp/study|60/60 cases"
  "accuracy|$bin/rocking_accuracy --quick --jobs 1 --records $tmp/one_record --out $tmp/acc overturn|2/2 record runs"
)
for run in "${runs[@]}"; do
  IFS='|' read -r name cmd shown <<< "$run"
  failed_before=$fail
  fail=0
  # off a terminal: stderr a file
  if ! $cmd > "$tmp/$name.file.out" 2> "$tmp/$name.file.err"; then
    echo "FAIL: $name exited with an error"; cat "$tmp/$name.file.err"; fail=1; continue
  fi
  if grep -q $'\r' "$tmp/$name.file.err" || grep -qE '\] +[0-9.]+%|left (--|[0-9])' "$tmp/$name.file.err"; then
    echo "FAIL: $name wrote progress off a terminal:"; cat -A "$tmp/$name.file.err"; fail=1
  fi
  # on a terminal: the bar reaches done == total; with --quiet nothing of it
  script -qec "$cmd > $tmp/$name.tty.out" /dev/null > "$tmp/$name.tty" 2>&1 < /dev/null
  if ! grep -qF "$shown" "$tmp/$name.tty" || ! grep -q 'left ' "$tmp/$name.tty"; then
    echo "FAIL: $name drew no progress ending at '$shown' on a terminal:"; cat -A "$tmp/$name.tty"; fail=1
  fi
  script -qec "$cmd --quiet > $tmp/$name.quiet.out" /dev/null > "$tmp/$name.quiet" 2>&1 < /dev/null
  if grep -q 'left ' "$tmp/$name.quiet"; then
    echo "FAIL: $name drew progress on a terminal with --quiet:"; cat -A "$tmp/$name.quiet"; fail=1
  fi
  # stdout is the same either way (the study and accuracy print their timing to stderr only)
  for how in tty quiet; do
    cmp -s "$tmp/$name.file.out" "$tmp/$name.$how.out" || { echo "FAIL: $name's stdout differs ($how)"; fail=1; }
  done
  [ $fail -eq 0 ] && echo "ok: $name: no progress off a terminal, '$shown' on one, none with --quiet"
  fail=$((fail | failed_before))
done
exit $fail
