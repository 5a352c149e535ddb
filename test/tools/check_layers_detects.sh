#!/usr/bin/env bash
# cmake/check_layers.cmake must fail, naming file and line, on a wrong-way include and on a ROS header
# in the core, and pass on a tree that keeps the rules. Run on a scratch tree, never the package.
#   check_layers_detects.sh PACKAGE_ROOT
set -u
root=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/include/rocking_monitor/physics" "$tmp/src/motion" "$tmp/src/model"
printf '#pragma once\n#include "rocking_monitor/constants.hpp"\n' > "$tmp/include/rocking_monitor/physics/ok.hpp"
printf '#include "rocking_monitor/physics/ok.hpp"\n#include "rocking_monitor/integrate/x.hpp"\n' > "$tmp/src/model/ok.cpp"
if ! cmake -DROOT="$tmp" -P "$root/cmake/check_layers.cmake"; then echo "FAIL: a clean tree was rejected"; exit 1; fi

printf '#pragma once\n\n#include "rocking_monitor/model/rocking_model.hpp"\n' > "$tmp/include/rocking_monitor/physics/bad.hpp"
printf '// comment\n#include <ros/ros.h>\n' > "$tmp/src/motion/bad.cpp"
out=$(cmake -DROOT="$tmp" -P "$root/cmake/check_layers.cmake" 2>&1)
status=$?
echo "$out"
[ "$status" -ne 0 ] || { echo "FAIL: wrong-way includes passed"; exit 1; }
grep -q 'include/rocking_monitor/physics/bad.hpp:3: layer physics includes rocking_monitor/model/rocking_model.hpp' <<<"$out" \
  || { echo "FAIL: the upward include was not named with file:line"; exit 1; }
grep -q 'src/motion/bad.cpp:2: ROS header <ros/ros.h>' <<<"$out" \
  || { echo "FAIL: the ROS header was not named with file:line"; exit 1; }
echo ok
