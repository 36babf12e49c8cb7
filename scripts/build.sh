#!/usr/bin/env bash
# Configures and builds anascan in ./build (Release unless BUILD_TYPE is set).
# With CI=true warnings are errors. Extra CMake options may be passed as arguments.
set -euo pipefail
cd "$(dirname "$0")/.."

werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
jobs="${JOBS:-$(nproc)}"

cmake -S . -B build -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" -DANASCAN_WERROR="$werror" "$@" >/dev/null
cmake --build build -j "$jobs"
