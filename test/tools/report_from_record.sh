#!/usr/bin/env bash
# scripts/report_from_record.sh on the bundled pulse record (CSV) and the example catalogue: the report
# the node writes names exactly the two items that overturn on this pulse (the demo's outcome, checked
# against the monitor's alarms by test/ros/report.test), and bad input is one error line.
set -uo pipefail
root="$1"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
html=$(bash "$root/scripts/report_from_record.sh" --catalogue "$root/config/catalogue_example.yaml" --out "$out" \
       --rate 2 -- --file "$root/bags/one_sine_pulse.csv" 2>"$out/stderr.txt" | tail -1)
[ -f "$html" ] || { echo "FAIL: no report written ($html); the script said:"; cat "$out/stderr.txt"; exit 1; }
banner=$(grep -o 'Overturned: [a-z_, ]*' "$html" | head -1)
[ "$banner" = "Overturned: shelving_unit, museum_vase" ] || { echo "FAIL: banner '$banner'"; exit 1; }
for item in medicine_cabinet monitor_cart shelving_unit incubator server_rack museum_vase; do
  grep -q ">$item<" "$html" || { echo "FAIL: $item not in the item table"; exit 1; }
done
err=$(bash "$root/scripts/report_from_record.sh" --catalogue /nonexistent.yaml --out "$out" -- --file x 2>&1); rc=$?
[ $rc -eq 2 ] && [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] && [[ "$err" == *"/nonexistent.yaml: no such file"* ]] ||
  { echo "FAIL: bad catalogue: rc $rc, '$err'"; exit 1; }
err=$(bash "$root/scripts/report_from_record.sh" --catalogue "$root/config/catalogue_example.yaml" --out "$out" -- --file /nonexistent.AT2 2>&1); rc=$?
[ $rc -eq 2 ] && [[ "$err" == *"record_to_bag failed"* ]] || { echo "FAIL: bad record: rc $rc, '$err'"; exit 1; }
echo "OK: $html: $banner"
