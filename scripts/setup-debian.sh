#!/usr/bin/env bash
# Install every Debian package that cutbench's build, tests and report need.
# Idempotent; run as root (or with sudo) on a fresh Debian 12 machine.
#   scripts/setup-debian.sh            build + tests + report (clang: the libFuzzer harnesses)
#   scripts/setup-debian.sh --browser  also Chromium (for report screenshots)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libgsl-dev libboost-test-dev libhdf5-dev
  libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libsuitesparse-dev
  python3 python3-numpy python3-matplotlib python3-h5py
  clang libclang-rt-14-dev libomp-14-dev
)
if [[ "${1:-}" == "--browser" ]]; then packages+=(chromium); fi

SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if (( ${#missing[@]} )); then
  echo "setup-debian: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup-debian: all ${#packages[@]} packages already installed"
fi

# The report needs Debian's python with h5py and matplotlib (not the python3 on PATH).
/usr/bin/python3 -c 'import h5py, matplotlib, numpy' \
  || { echo "setup-debian: /usr/bin/python3 cannot import h5py/matplotlib/numpy" >&2; exit 1; }
