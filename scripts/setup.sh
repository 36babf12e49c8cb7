#!/usr/bin/env bash
# Installs every build and test dependency of anascan from Debian 12 packages.
# Idempotent: when everything is present it only checks and returns (about a second).
# Uses sudo only when not running as root.
set -euo pipefail

PACKAGES=(
    build-essential cmake pkg-config ninja-build git
    clang libclang-rt-14-dev           # libFuzzer targets
    libeigen3-dev libnanoflann-dev libtbb-dev
    libqhull-dev                       # processing: convex hull of a stone (coverage)
    libcgal-dev                        # processing: efficient RANSAC planes of block features
    coinor-libclp-dev                  # peer of the block-assembly QP solver (test and benchmark only)
    libopencv-dev libopencv-contrib-dev
    libjpeg-dev libpng-dev             # drivers: grey images read and written without imgcodecs
    libembree-dev                      # ray caster of the simulated scanners (sim/)
    libusb-1.0-0-dev libv4l-dev
    libglfw3-dev libimgui-dev libgl-dev libgl1-mesa-dri
    libsqlite3-dev sqlite3
    libspdlog-dev libfmt-dev libcli11-dev nlohmann-json3-dev
    libgtest-dev libgmock-dev googletest libbenchmark-dev
    umockdev libumockdev-dev
    libexpat1-dev                      # processing: the XML section of E57 files
    zlib1g-dev libx11-dev              # drivers: recording CRC-32; projector test reads the X screen
    xvfb xauth
    fonts-dejavu-core                  # gui: anascan-field's large readable font (DejaVu Sans)
    python3-open3d python3-numpy       # peer for the side-by-side benchmarks
    libopen3d-dev                      # Open3D C++: screened Poisson (processing/surface); peer of the benchmarks
    openmpi-bin libopenmpi-dev         # campaigns over MPI (acquisition/campaign; optional at build time)
)

missing=()
for pkg in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "ok installed"; then
        missing+=("$pkg")
    fi
done

if [ ${#missing[@]} -eq 0 ]; then
    echo "setup: all ${#PACKAGES[@]} Debian packages present"
    exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null; then
        SUDO="sudo"
    else
        echo "setup: need root or sudo to install: ${missing[*]}" >&2
        exit 1
    fi
fi

echo "setup: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
