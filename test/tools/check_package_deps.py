#!/usr/bin/env python3
"""package.xml and scripts/install_deps.sh must name the same dependencies (issue 30 part 1).

Each Debian package install_deps.sh installs must be declared in package.xml under its rosdep key,
and each key package.xml declares must be installed by install_deps.sh: otherwise rosdep/bloom users
and `bash scripts/run_tests.sh` users get different packages. Exits 1 naming every mismatch.

  check_package_deps.py PACKAGE_ROOT
  check_package_deps.py --package-xml FILE --install-deps FILE
"""
import re
import sys
import xml.etree.ElementTree as ET

# Debian name -> rosdep key, only where they differ (keys from ros/rosdistro rosdep/base.yaml,
# python.yaml, and the ROS package names for Debian's ROS 1 packages). A name not here is its own key.
ROSDEP_KEY = {
    'libeigen3-dev': 'eigen',
    'libcli11-dev': 'cli11',
    'nlohmann-json3-dev': 'nlohmann-json-dev',
    'libyaml-cpp-dev': 'yaml-cpp',
    'libtbb-dev': 'tbb',
    'zlib1g-dev': 'zlib',
    'libgtest-dev': 'gtest',
    'libbenchmark-dev': 'benchmark',
    'chromium': 'chromium-browser',
    'ros-core-dev': 'ros_core',
    'libroscpp-dev': 'roscpp',
    'librosbag-dev': 'rosbag',
    'python3-rosbag': 'rosbag',
    'librostest-dev': 'rostest',
    'python3-rostest': 'rostest',
    'python3-roslaunch': 'roslaunch',
    'python3-rosmaster': 'rosmaster',
    'python3-rostopic': 'rostopic',
    'ros-message-generation': 'message_generation',
    'ros-message-runtime': 'message_runtime',
    'ros-std-msgs': 'std_msgs',
    'ros-std-srvs': 'std_srvs',
    'libstd-srvs-dev': 'std_srvs',
    'python3-std-srvs': 'std_srvs',
    'ros-geometry-msgs': 'geometry_msgs',
    'ros-sensor-msgs': 'sensor_msgs',
    'python3-sensor-msgs': 'sensor_msgs',
    'ros-visualization-msgs': 'visualization_msgs',
    'ros-diagnostic-msgs': 'diagnostic_msgs',
    'python3-diagnostic-msgs': 'diagnostic_msgs',
    'libdiagnostic-updater-dev': 'diagnostic_updater',
    'libnodeletlib-dev': 'nodelet',
    'libnodeletlib-tools': 'nodelet',
    'libtf2-dev': 'tf2',
    'libtf2-ros-dev': 'tf2_ros',
    'libtf2-msgs-dev': 'tf2_msgs',
    'libtf2-eigen-dev': 'tf2_eigen',
    'tf2-tools': 'tf2_tools',
    'topic-tools': 'topic_tools',
    'libcurl4-openssl-dev': 'libcurl-dev',
    'libssl-dev': 'openssl',  # OpenSSL's libcrypto (issue 52's HMAC); rosdep's key for it
}

# Installed but never declared, and why: no ROS package declares these.
NOT_DECLARED = {
    'build-essential': 'the compiler toolchain, which rosdep and bloom presume (rosdistro has no key)',
    'git': 'fetches the sources; no build step or test runs it',
}

DEPEND_TAGS = ('depend', 'build_depend', 'build_export_depend', 'buildtool_depend', 'exec_depend',
               'test_depend', 'doc_depend', 'run_depend', 'buildtool_export_depend')


def installed_packages(path):
    """The words of the packages=( ... ) array in install_deps.sh, comments dropped."""
    text = open(path, encoding='utf-8').read()
    m = re.search(r'^packages=\((.*?)^\)', text, re.S | re.M)
    if not m:
        sys.exit(f'check_package_deps: no packages=( ... ) array in {path}')
    words = []
    for line in m.group(1).splitlines():
        words += line.split('#', 1)[0].split()
    if not words:
        sys.exit(f'check_package_deps: the packages array in {path} is empty')
    return words


def declared_keys(path):
    root = ET.parse(path).getroot()
    return {e.text.strip() for tag in DEPEND_TAGS for e in root.iter(tag) if e.text and e.text.strip()}


def main(argv):
    if len(argv) == 2:
        xml_path, deps_path = argv[1] + '/package.xml', argv[1] + '/scripts/install_deps.sh'
    elif len(argv) == 5 and argv[1] == '--package-xml' and argv[3] == '--install-deps':
        xml_path, deps_path = argv[2], argv[4]
    else:
        sys.exit(__doc__)
    debs = installed_packages(deps_path)
    keys = declared_keys(xml_path)

    errors = []
    provided = set()  # keys some installed package stands for
    for deb in debs:
        if deb in NOT_DECLARED:
            continue
        key = ROSDEP_KEY.get(deb, deb)
        provided.add(key)
        if key not in keys:
            how = f' under its rosdep key "{key}"' if key != deb else ''
            errors.append(f'{deps_path} installs {deb}, but {xml_path} does not declare it{how}')
    for key in sorted(keys - provided):
        debs_for_key = sorted(d for d, k in ROSDEP_KEY.items() if k == key) or [key]
        errors.append(f'{xml_path} declares {key}, but {deps_path} does not install it '
                      f'(Debian: {" or ".join(debs_for_key)})')
    # A table entry for a package no longer installed is dead weight that hides the next mistake.
    for deb in sorted(set(ROSDEP_KEY) | set(NOT_DECLARED)):
        if deb not in debs:
            errors.append(f'check_package_deps.py maps {deb}, which {deps_path} no longer installs')

    for e in errors:
        print('MISMATCH: ' + e)
    if errors:
        return 1
    print(f'ok: {len(debs)} Debian packages installed, {len(keys)} rosdep keys declared, in step')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
