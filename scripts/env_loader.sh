#!/usr/bin/env bash
# roslaunch env-loader for <machine> tags (launch/sharded.launch): sets up this package's ROS
# environment on the machine that runs a monitor shard, then runs the node roslaunch asked for.
# On a remote machine the package must be built at the same path (or pass env_loader:=...).
set +u
export PATH=/usr/bin:$PATH
source "$(cd "$(dirname "$0")/.." && pwd)/build/devel/setup.bash"
exec "$@"
