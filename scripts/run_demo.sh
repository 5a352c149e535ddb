#!/usr/bin/env bash
# The main job on the bundled default (README): installs what is missing, builds, and replays the
# bundled one-sine-pulse bag through the example hospital catalogue with the live monitor, printing a
# per-item table while it rocks and the alarm summary at the end (about 15 s).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
echo "building (log: build/build.log) ..."
mkdir -p build
bash scripts/build.sh >build/build.log 2>&1 || { tail -40 build/build.log; exit 1; }
export PATH=/usr/bin:$PATH
set +u
source build/devel/setup.bash
set -u
export ROS_HOME=${ROS_HOME:-$PWD/build/ros_home}
exec roslaunch rocking_monitor demo.launch "$@"
