#!/bin/bash
# The import-circle check must fail on a circle: a.py imports b, b (lazily) imports a; c.py is clean.
set -u
ROOT=${1:-$(dirname "$0")/../..}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf 'import b\n' > "$tmp/a.py"
printf 'def f():\n    from a import x\n    return x\n' > "$tmp/b.py"
printf 'import os\nimport a\n' > "$tmp/c.py"
out=$(/usr/bin/python3 "$ROOT/test/tools/check_script_imports.py" "$tmp")
rc=$?
echo "$out"
if [ "$rc" -ne 1 ]; then echo "FAIL: exit $rc on a circle, expected 1"; exit 1; fi
if ! grep -q "import circle: a b (a -> b, b -> a)" <<<"$out"; then echo "FAIL: the circle a b is not named"; exit 1; fi
if grep -q "\bc\b" <<<"$out"; then echo "FAIL: c.py is not in the circle but is named"; exit 1; fi
rm "$tmp/b.py"; printf 'import os\n' > "$tmp/b.py"
/usr/bin/python3 "$ROOT/test/tools/check_script_imports.py" "$tmp" || { echo "FAIL: no circle but exit non-zero"; exit 1; }
echo "PASS"
