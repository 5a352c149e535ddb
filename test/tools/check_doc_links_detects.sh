#!/usr/bin/env bash
# check_doc_links.py must fail on a dead file link and on a dead #anchor, naming page and line, and
# pass on links that resolve. Runs on a scratch tree, never the package's own pages.
#   check_doc_links_detects.sh PACKAGE_ROOT
set -u
root=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/docs"
printf '# Top\n\nSee [the page](docs/page.md#two-planes-a-b) and [index](docs/README.md).\n' > "$tmp/README.md"
printf '# Index\n\n[back](../README.md#top)\n' > "$tmp/docs/README.md"
printf '# Page\n\n## Two planes (a, b)\n\n```\n## not a heading\n```\n' > "$tmp/docs/page.md"
/usr/bin/python3 "$root/test/tools/check_doc_links.py" "$tmp" || { echo "FAIL: resolving links were rejected"; exit 1; }

printf '\n[gone](missing.md) and [code](page.md#not-a-heading)\n' >> "$tmp/docs/README.md"
out=$(/usr/bin/python3 "$root/test/tools/check_doc_links.py" "$tmp" 2>&1)
status=$?
echo "$out"
[ "$status" -ne 0 ] || { echo "FAIL: dead links passed"; exit 1; }
grep -q 'docs/README.md:5: link to missing.md: no such file' <<<"$out" || { echo "FAIL: the dead file link was not named"; exit 1; }
grep -q 'docs/README.md:5: link to page.md#not-a-heading: no heading #not-a-heading in docs/page.md' <<<"$out" \
  || { echo "FAIL: the dead anchor (a heading inside a code block) was not named"; exit 1; }
echo ok
