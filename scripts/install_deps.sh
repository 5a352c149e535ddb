#!/usr/bin/env bash
# Installs everything rocking_monitor needs on Debian 12 (Debian's own ROS 1 packages; no /opt/ros).
# Safe to re-run: apt-get skips what is already there.
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  libeigen3-dev libcli11-dev nlohmann-json3-dev libyaml-cpp-dev libtbb-dev libcsv-dev libmseed-dev
  libgtest-dev libgmock-dev libbenchmark-dev libsundials-dev libhwy-dev
  python3-matplotlib python3-numpy python3-yaml python3-scipy parallel
  python3-meshio assimp-utils python3-tqdm
  catkin ros-core-dev libroscpp-dev librosbag-dev librostest-dev python3-rostest
  python3-roslaunch python3-rosmaster python3-rosbag python3-rostopic python3-diagnostic-msgs rosbash ros-message-generation ros-message-runtime
  ros-std-msgs ros-std-srvs libstd-srvs-dev ros-geometry-msgs ros-sensor-msgs
  ros-visualization-msgs ros-diagnostic-msgs libdiagnostic-updater-dev libnodeletlib-dev libnodeletlib-tools
  libtf2-dev libtf2-ros-dev libtf2-msgs-dev libtf2-eigen-dev tf2-tools python3-sensor-msgs python3-std-srvs
  topic-tools
  libcpp-httplib-dev chromium
  zlib1g-dev
  libbullet-dev libsiconos-numerics-dev
  libcurl4-openssl-dev libmosquitto-dev mosquitto python3-aiosmtpd
  libssl-dev  # OpenSSL libcrypto: HMAC-SHA256 of authenticated datagrams (udp_accel_bridge ~key_file)
  openssl     # the openssl command: the notifier's TLS tests make their certificates (priority optional: not in a minimal image)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install_deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install_deps: done"
