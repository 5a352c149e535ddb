#!/bin/bash
# rocking_experiments on the first 4 shared shaking-table tests: its accounting (every test x specimen
# predicted once, the printed confusion counts equal the CSV's rows) -- not whether it is right.
# Exit 77 (skipped) when the third-party data is absent.
set -u
exe=$1 dir=$2 catalogue=$3
if [ ! -f "$dir/outcomes.csv" ]; then echo "SKIP: $dir not found (shaking-table tests skipped)"; exit 77; fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$exe" "$dir" --catalogue "$catalogue" --max-tests 4 --out "$tmp/t.csv" > "$tmp/out.txt" || { cat "$tmp/out.txt"; exit 1; }
cat "$tmp/out.txt"
fail=0
rows=$(($(wc -l < "$tmp/t.csv") - 1))
[ "$rows" -eq 8 ] || { echo "FAIL: $rows rows, expected 4 tests x 2 specimens"; fail=1; }
for sp in SP1 SP2; do
  for kind in TP FP TN FN; do
    case $kind in TP) p=1 m=1;; FP) p=1 m=0;; TN) p=0 m=0;; FN) p=0 m=1;; esac
    want=$(awk -F, -v s=$sp -v p=$p -v m=$m 'NR>1 && $2==s && $10==p && $11==m' "$tmp/t.csv" | wc -l)
    got=$(grep -E "^$sp +tests" "$tmp/out.txt" | sed -E "s/.* $kind +([0-9]+).*/\1/")
    [ "$got" = "$want" ] || { echo "FAIL: $sp $kind printed $got, table has $want"; fail=1; }
  done
  grep -qE "^$sp +tests +4 " "$tmp/out.txt" || { echo "FAIL: $sp not scored on 4 tests"; fail=1; }
done
grep -qE "^all +tests +8 " "$tmp/out.txt" || { echo "FAIL: all not 8"; fail=1; }
# the tests start with Test011..Test014: the table rows name them in order
[ "$(awk -F, 'NR==2{print $1}' "$tmp/t.csv")" = "11" ] || { echo "FAIL: first row is not test 11"; fail=1; }
# An ensemble of two identical SP2 members (SP2#0, SP2#1): one row per test, members 2, and
# P(overturn) equal to the single member's 0/1 prediction.
sed -n '/id: SP2/,$p' "$catalogue" | sed 's/id: SP2/id: SP2#0/' > "$tmp/member.yaml"
{ echo "items:"; cat "$tmp/member.yaml"; sed 's/SP2#0/SP2#1/' "$tmp/member.yaml"; } > "$tmp/ens.yaml"
"$exe" "$dir" --catalogue "$tmp/ens.yaml" --max-tests 4 --out "$tmp/e.csv" > "$tmp/e.txt" || { cat "$tmp/e.txt"; exit 1; }
[ "$(($(wc -l < "$tmp/e.csv") - 1))" -eq 4 ] || { echo "FAIL: ensemble rows"; fail=1; }
awk -F, 'NR>1 { if ($12 != 2 || $13 + 0 != $10) bad = 1 } END { exit bad }' "$tmp/e.csv" ||
  { echo "FAIL: ensemble members/P"; cat "$tmp/e.csv"; fail=1; }
paste -d, <(awk -F, 'NR>1 && $2=="SP2" {print $10}' "$tmp/t.csv") <(awk -F, 'NR>1 {print $10}' "$tmp/e.csv") |
  awk -F, '$1 != $2 { bad = 1 } END { exit bad }' || { echo "FAIL: ensemble of copies differs from SP2"; fail=1; }
grep -qE "^SP2 +Brier" "$tmp/e.txt" || { echo "FAIL: no Brier line"; fail=1; }
exit $fail
