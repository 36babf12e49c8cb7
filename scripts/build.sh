#!/usr/bin/env bash
# Configures and builds anascan in ./build (Release unless BUILD_TYPE is set).
# With CI=true warnings are errors. Extra CMake options may be passed as arguments.
set -euo pipefail
cd "$(dirname "$0")/.."

werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
jobs="${JOBS:-$(nproc)}"

# ccache, when the machine has it (a developer's does; CI's clean machine does not), makes
# rebuilds after a branch switch or in a second clone cheap.
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

cmake -S . -B build -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" -DANASCAN_WERROR="$werror" \
    "${launcher[@]}" "$@" >/dev/null
cmake --build build -j "$jobs"
