#!/usr/bin/env bash
# check_package_deps.py must fail, naming the package, when package.xml and install_deps.sh disagree
# either way. Runs on scratch copies, never the package's own files.
#   check_package_deps_detects.sh PACKAGE_ROOT
set -u
root=$1
check="/usr/bin/python3 $root/test/tools/check_package_deps.py"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# expect_mismatch NAME XML DEPS PATTERN: the check exits 1 and prints PATTERN.
expect_mismatch() {
  out=$($check --package-xml "$2" --install-deps "$3" 2>&1)
  status=$?
  echo "$out"
  [ "$status" -eq 1 ] || fail "$1: exit status $status, not 1"
  grep -q -- "$4" <<<"$out" || fail "$1: no line matching '$4'"
}

$check --package-xml "$root/package.xml" --install-deps "$root/scripts/install_deps.sh" || fail "the package itself"

# A library installed but not declared (its Debian name is its key).
grep -v '<depend>libmseed-dev</depend>' "$root/package.xml" > "$tmp/no_mseed.xml"
expect_mismatch "undeclared libmseed-dev" "$tmp/no_mseed.xml" "$root/scripts/install_deps.sh" \
  'installs libmseed-dev, but .* does not declare it'

# Installed but not declared, where the key differs from the Debian name.
grep -v '<depend>zlib</depend>' "$root/package.xml" > "$tmp/no_zlib.xml"
expect_mismatch "undeclared zlib" "$tmp/no_zlib.xml" "$root/scripts/install_deps.sh" \
  'installs zlib1g-dev, but .* does not declare it under its rosdep key "zlib"'

# Declared but never installed.
sed 's#<exec_depend>parallel</exec_depend>#&<exec_depend>python3-pandas</exec_depend>#' "$root/package.xml" > "$tmp/pandas.xml"
expect_mismatch "uninstalled python3-pandas" "$tmp/pandas.xml" "$root/scripts/install_deps.sh" \
  'declares python3-pandas, but .* does not install it'

# A dependency dropped from install_deps.sh: its key is declared but nothing installs it.
sed 's/ libtbb-dev / /' "$root/scripts/install_deps.sh" > "$tmp/no_tbb.sh"
grep -q libtbb-dev "$tmp/no_tbb.sh" && fail "the scratch install_deps.sh still installs libtbb-dev"
expect_mismatch "uninstalled tbb" "$root/package.xml" "$tmp/no_tbb.sh" \
  'declares tbb, but .* does not install it (Debian: libtbb-dev)'
echo ok
