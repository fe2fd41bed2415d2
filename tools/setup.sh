#!/usr/bin/env bash
# Installs every Debian package coinroll needs to build, test, render and chart.
# Idempotent: skips apt entirely when everything is already installed.
set -euo pipefail

packages=(
  cmake g++ pkg-config make
  libeigen3-dev nlohmann-json3-dev libcli11-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libosmesa6-dev libglm-dev libstb-dev zlib1g-dev
  fonts-dejavu-core  # the overlay font, embedded in the binary at build time (DejaVuSansMono.ttf)
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri  # EGL back ends: glvnd's libEGL, Mesa's vendor and its llvmpipe
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  ffmpeg
  libboost-dev libsundials-dev
  python3 python3-matplotlib python3-numpy python3-scipy python3-sympy
  python3-dev pybind11-dev python3-pybind11 python3-pytest  # the Python module (python/) and its tests
  parallel
  slurm-wlm munge  # tests/slurm/slurm_test.py starts a one-node Slurm
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
