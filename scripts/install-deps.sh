#!/usr/bin/env bash
# Installs the Debian packages scanloc builds with; does nothing when they are all present.
set -euo pipefail
packages=(build-essential cmake pkg-config libeigen3-dev libnanoflann-dev libceres-dev libpcl-dev
          libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev zlib1g-dev
          librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev libtf2-msgs-dev libbz2-dev  # ROS 1 bags
          python3-rosbag python3-sensor-msgs python3-nav-msgs python3-tf2-msgs  # scripts/make-bag.py
          chromium)  # chromium: the report's browser test (tests/report_browser_test.cpp)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]} (libpcl-dev pulls in ~500 packages, about a minute)"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
