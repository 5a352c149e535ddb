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
# A package beside the scripts (as scripts/event_report): its __init__ importing its modules and a
# script importing them is no circle; two of its modules importing each other (relative imports) is.
mkdir "$tmp/p"
printf 'from .x import f\n' > "$tmp/p/__init__.py"
printf 'from .y import g\n\ndef f():\n    return g()\n' > "$tmp/p/x.py"
printf 'def g():\n    return 1\n' > "$tmp/p/y.py"
printf 'from p.x import f\n' > "$tmp/d.py"
/usr/bin/python3 "$ROOT/test/tools/check_script_imports.py" "$tmp" || { echo "FAIL: a package's re-exports called a circle"; exit 1; }
printf 'def g():\n    from . import x\n    return x\n' > "$tmp/p/y.py"
out=$(/usr/bin/python3 "$ROOT/test/tools/check_script_imports.py" "$tmp")
rc=$?
echo "$out"
if [ "$rc" -ne 1 ]; then echo "FAIL: exit $rc on a circle inside a package, expected 1"; exit 1; fi
if ! grep -q "import circle: p.x p.y (p.x -> p.y, p.y -> p.x)" <<<"$out"; then echo "FAIL: the circle p.x p.y is not named"; exit 1; fi
echo "PASS"
