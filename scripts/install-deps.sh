#!/bin/sh
# Installs the Debian bookworm packages rpvio needs. Idempotent: a no-op when all are present.
# Run as root (or through sudo). Usage: scripts/install-deps.sh [extra packages]
set -eu

PACKAGES="cmake g++ make pkg-config libmrpt-dev mrpt-apps libceres-dev libopencv-dev \
liboctomap-dev libeigen3-dev libdeflate-dev libgoogle-perftools-dev libgtest-dev libgmock-dev libbenchmark-dev \
librosbag-storage-dev libbz2-dev libsensor-msgs-dev libnav-msgs-dev libroscpp-core-dev $*"

missing=""
for pkg in $PACKAGES; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $pkg"
  fi
done

if [ -z "$missing" ]; then
  echo "install-deps: all dependencies present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing$missing"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
# shellcheck disable=SC2086
$SUDO apt-get install -y -q --no-install-recommends $missing
