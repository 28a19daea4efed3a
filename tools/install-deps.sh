#!/usr/bin/env bash
# Installs FragMPM's build and test dependencies on Debian 12 (all from Debian's archive).
set -euo pipefail
packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libhdf5-dev hdf5-tools libopencv-dev libcgal-dev libosmesa6-dev
  libgtest-dev libtomlplusplus-dev libcli11-dev libfmt-dev libomp-dev
  libxdmf-dev libxml2-dev libboost-dev
  libopenmpi-dev openmpi-bin
  clang-format fonts-dejavu-core
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi
