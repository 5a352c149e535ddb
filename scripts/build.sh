#!/usr/bin/env bash
# Configures and builds the package (core library, tools, ROS nodes, tests) into ./build.
# Debian's ROS Python modules live under /usr/bin/python3, not a pyenv/venv python.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH=/usr/bin:$PATH
mkdir -p build
cmake -S . -B build -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
# catkin builds rostest executables only with its 'tests' target.
targets=$(cmake --build build --target help)  # not piped into grep -q: SIGPIPE under pipefail
if grep -q '^\.\.\. tests$' <<<"$targets"; then
  cmake --build build --target tests -j"$(nproc)"
fi
