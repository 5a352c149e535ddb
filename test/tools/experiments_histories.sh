#!/bin/bash
# rocking_experiments --histories on the first 4 shared shaking-table tests: one history per requested
# test and specimen, the first row at rest, one row per table sample stepped (record + 5 s tail, or up to
# the overturn), the history's max |theta|/alpha equal to the table's column; 'misses' writes exactly
# the wrong predictions; a test not run is an error. Exit 77 (skipped) when the data is absent.
set -u
exe=$1 dir=$2 catalogue=$3
if [ ! -f "$dir/outcomes.csv" ]; then echo "SKIP: $dir not found (shaking-table tests skipped)"; exit 77; fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
"$exe" "$dir" --catalogue "$catalogue" --max-tests 4 --out "$tmp/t.csv" --histories "$tmp/h" \
  --history-tests 11,13 > "$tmp/out.txt" || { cat "$tmp/out.txt"; exit 1; }
cat "$tmp/out.txt"
n=$(ls "$tmp/h" | wc -l)
[ "$n" -eq 4 ] || { echo "FAIL: $n histories, expected 2 tests x 2 specimens"; ls "$tmp/h"; fail=1; }
grep -q "4 histories written" "$tmp/out.txt" || { echo "FAIL: count not printed"; fail=1; }
for t in 11 13; do
  samples=$(($(zcat "$dir/tests/Test0$t.csv.gz" | grep -c .) - 1))
  # the tail: ceil(5 s / dt), dt from the record's span as the tool computes it (~4000 at 800 Hz)
  tail=$(zcat "$dir/tests/Test0$t.csv.gz" | awk -F, 'NR==2 { t0 = $1 } NR>1 && NF==2 { t1 = $1; n++ }
    END { x = 5.0 / ((t1 - t0) / (n - 1)); c = int(x); if (x > c) c++; print c }')
  for sp in SP1 SP2; do
    h="$tmp/h/Test0${t}_$sp.csv"
    [ -f "$h" ] || { echo "FAIL: no $h"; fail=1; continue; }
    # first row: t = 0 at rest
    awk -F, 'NR==2 { exit !($1 == 0 && $3 == 0 && $4 == 0 && $5 == 0 && $6 == 0 && $7 == "REST") }' "$h" ||
      { echo "FAIL: $h first row not at rest: $(sed -n 2p "$h")"; fail=1; }
    row=$(awk -F, -v t=$t -v s=$sp 'NR>1 && $1==t && $2==s' "$tmp/t.csv")
    table_max=$(echo "$row" | cut -d, -f7)
    overturned=$(echo "$row" | cut -d, -f10)
    rows=$(($(wc -l < "$h") - 1))
    # record samples (the first is the reset) + the tail at rest, unless it overturned earlier
    if [ "$overturned" = 0 ]; then
      [ "$rows" -eq $((samples + tail)) ] || { echo "FAIL: $h has $rows rows, expected $samples + $tail"; fail=1; }
    else
      [ "$rows" -le $((samples + tail)) ] || { echo "FAIL: $h has $rows rows after an overturn"; fail=1; }
    fi
    # the history's running max at the end equals the table (6 significant digits); no sample above it
    awk -F, -v m="$table_max" 'NR>1 { last = $6; if ($5 > $6 * (1 + 1e-7) + 1e-12) bad = 1 }
      END { d = last - m; if (d < 0) d = -d; exit !(bad == 0 && d <= 1e-5 * m + 1e-9) }' "$h" ||
      { echo "FAIL: $h max ratio $(tail -1 "$h" | cut -d, -f6) vs table $table_max"; fail=1; }
  done
done
# 'misses': exactly the wrong predictions of the table
"$exe" "$dir" --catalogue "$catalogue" --max-tests 4 --out "$tmp/t2.csv" --histories "$tmp/m" \
  --history-every 8 > "$tmp/m.txt" || { cat "$tmp/m.txt"; exit 1; }
want=$(awk -F, 'NR>1 && $11 != "" && $10 != $11' "$tmp/t2.csv" | wc -l)
got=$(ls "$tmp/m" | wc -l)
[ "$got" -eq "$want" ] || { echo "FAIL: misses: $got histories, table has $want wrong predictions"; fail=1; }
grep -q "$want histories written" "$tmp/m.txt" || { echo "FAIL: misses count not printed"; fail=1; }
# a test that was not run is an error naming it
if "$exe" "$dir" --catalogue "$catalogue" --max-tests 2 --histories "$tmp/x" --history-tests 11,999 \
     > "$tmp/x.txt" 2>&1; then echo "FAIL: test 999 accepted"; fail=1; fi
grep -q "test 999 is not among the tests run" "$tmp/x.txt" || { echo "FAIL: message: $(cat "$tmp/x.txt")"; fail=1; }
exit $fail
