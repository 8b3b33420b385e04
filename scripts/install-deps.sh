#!/usr/bin/env bash
# Installs every Debian package relight needs to build, test and run.
# Idempotent and non-interactive: packages already present are skipped.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build
  libembree-dev libopenimageio-dev openimageio-tools libassimp-dev
  nlohmann-json3-dev libeigen3-dev libtbb-dev libcli11-dev
  libspdlog-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev
  qt6-base-dev libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  xvfb xauth
  libxxhash-dev                      # content hashes of the analysis inputs
  libopencv-dev                      # registration (Canny, distance transforms), hdr-merge (photo module), probe-from-photo (HoughCircles)
  blender                            # blender_test: the Blender exporter (about a minute to install)
  python3-openimageio python3-numpy  # bench/*.py scripts that read and write images (upsample_scene.py)
  slurmctld slurmd slurm-client munge  # farm_slurm_test: relight farm through a Slurm started on this machine
  clang-14 libclang-rt-14-dev llvm-14  # asan preset and its fuzz targets: clang, libFuzzer, llvm-symbolizer
  lld                                # links about three times faster than ld (CMakeLists.txt)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
