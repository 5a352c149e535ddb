#!/usr/bin/env bash
# The package as a ROS user gets it from an install space (issue 30 part 2): installed into a scratch
# prefix and used from there alone, with neither the source nor the build tree on any path:
#  1. every node the launch files start is an executable of the install space;
#  2. the command-line tools run (--help) from there;
#  3. roslaunch resolves demo.launch and monitor.launch to files of the install space only;
#  4. a downstream package finds rocking_monitor with find_package(catkin COMPONENTS rocking_monitor),
#     builds against the installed core headers, libraries and message headers, and runs: it reads a
#     record (CSV) and steps a body through it.
#   install_space.sh PACKAGE_ROOT BUILD_DIR
set -u
root=$(cd "$1" && pwd)
build=$(cd "$2" && pwd)
prefix=$(mktemp -d /tmp/rocking_install.XXXXXX)
trap 'rm -rf "$prefix"' EXIT
errors=0
fail() { echo "FAIL: $*"; errors=$((errors + 1)); }

cmake --install "$build" --prefix "$prefix/install" >"$prefix/install.log" 2>&1 \
  || { tail -20 "$prefix/install.log"; echo "FAIL: cmake --install"; exit 1; }
inst=$prefix/install

# Only the install space and the system: no devel space, no source package on the package path.
export PATH=/usr/bin:/bin
export ROS_PACKAGE_PATH=$inst/share
export CMAKE_PREFIX_PATH=$inst:/usr
export LD_LIBRARY_PATH=$inst/lib
export PYTHONPATH=$inst/lib/python3/dist-packages
export ROS_HOME=$prefix/ros_home
cd "$prefix"

# 1. The nodes of the launch files.
nodes=$(/usr/bin/python3 - "$inst/share/rocking_monitor/launch" <<'EOF'
import glob, sys, xml.etree.ElementTree as ET
types = set()
for f in glob.glob(sys.argv[1] + '/*.launch'):
    types |= {n.get('type') for n in ET.parse(f).getroot().iter('node') if n.get('pkg') == 'rocking_monitor'}
print('\n'.join(sorted(types)))
EOF
)
[ -n "$nodes" ] || fail "no launch files installed in share/rocking_monitor/launch"
for node in $nodes; do
  [ -x "$inst/lib/rocking_monitor/$node" ] || fail "a launch file starts $node, which is not installed in lib/rocking_monitor"
done

# 2. The tools.
for tool in rocking_sim rocking_study rocking_experiments record_to_bag record_to_mseed rocking_report rocking_catalogue catalogue_check; do
  if [ ! -x "$inst/lib/rocking_monitor/$tool" ]; then
    fail "$tool is not installed in lib/rocking_monitor"
  elif ! "$inst/lib/rocking_monitor/$tool" --help >"$prefix/help.txt" 2>&1; then
    fail "$tool --help from the install space: $(head -3 "$prefix/help.txt")"
  fi
done

# 3. roslaunch resolves the launch files (their includes, catalogues and bags) in the install space.
for launch in demo.launch monitor.launch; do
  if ! files=$(roslaunch --files rocking_monitor "$launch" 2>&1); then
    fail "roslaunch --files rocking_monitor $launch: $files"
  elif grep -v "^$inst/" <<<"$files" | grep -q .; then
    fail "roslaunch rocking_monitor $launch reads files outside the install space: $(grep -v "^$inst/" <<<"$files")"
  fi
done

# 4. A downstream package.
mkdir -p "$prefix/downstream"
cat >"$prefix/downstream/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(downstream CXX)
set(CMAKE_CXX_STANDARD 17)
find_package(catkin REQUIRED COMPONENTS rocking_monitor)
add_executable(downstream main.cpp)
target_include_directories(downstream PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(downstream PRIVATE ${catkin_LIBRARIES})
EOF
cat >"$prefix/downstream/main.cpp" <<'EOF'
// A downstream node's first lines: a core record reader and simulation, and a message header.
#include <cstdio>
#include <fstream>

#include <rocking_monitor/OverturnAlarm.h>

#include "rocking_monitor/monitoring/simulation.hpp"
#include "rocking_monitor/motion/ground_motion.hpp"
#include "rocking_monitor/motion/record_reader.hpp"

int main() {
  namespace rm = rocking_monitor::core;
  {
    std::ofstream csv("pulse.csv");
    for (int i = 0; i <= 200; ++i) csv << i * 0.01 << "," << (i >= 20 && i < 70 ? 4.0 : 0.0) << "\n";
  }
  const std::vector<rm::Component> c = rm::read_record("pulse.csv");
  const rm::GroundMotion motion = rm::make_ground_motion(c.at(0), nullptr, 1.0);
  rm::BodyParameters p;
  p.width = 0.15;
  p.cg_height = 0.35;
  const rm::SimulationResult r = rm::simulate(rm::Body(p), rm::SolverSettings{}, motion, false);
  rocking_monitor::OverturnAlarm alarm;
  alarm.level = r.outcome.overturned ? rocking_monitor::OverturnAlarm::OVERTURNED : 0;
  std::printf("samples %ld, max rotation ratio %.3f, overturned %d\n", r.outcome.samples,
              r.outcome.max_rotation_ratio, static_cast<int>(r.outcome.overturned));
  // every input interval stepped, and the pulse rocked it
  return r.outcome.samples == static_cast<long>(motion.size()) - 1 && r.outcome.max_rotation_ratio > 0.0 ? 0 : 1;
}
EOF
if ! cmake -S "$prefix/downstream" -B "$prefix/downstream/build" -DCMAKE_BUILD_TYPE=Release \
       >"$prefix/downstream.log" 2>&1; then
  fail "a downstream package cannot find rocking_monitor: $(grep -m3 -iE 'error|not found|could not' "$prefix/downstream.log")"
elif ! cmake --build "$prefix/downstream/build" >>"$prefix/downstream.log" 2>&1; then
  fail "a downstream package does not build against the install space: $(grep -m5 -iE 'error|undefined' "$prefix/downstream.log")"
elif ! (cd "$prefix/downstream/build" && ./downstream); then
  fail "the downstream program failed"
fi

if [ "$errors" -ne 0 ]; then
  echo "$errors problem(s) with the install space"
  exit 1
fi
echo "ok: install space has every launched node ($(echo $nodes | wc -w)), the tools, resolvable launch files, and builds a downstream package"
