#!/usr/bin/env bash
# Installs the Debian packages pastemix needs, only those that are missing. Safe to run again.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev libhdf5-dev libfmt-dev doctest-dev libcli11-dev libtomlplusplus-dev
  python3-matplotlib python3-h5py python3-numpy
  libopenmpi-dev openmpi-bin   # optional (app/study/ranks.h): studies over MPI ranks; the build works without
)
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
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
