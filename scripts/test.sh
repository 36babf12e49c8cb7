#!/usr/bin/env bash
# Set up, build and run the whole test suite (all labels except `hw`, which needs real
# hardware). Tests labelled `data` skip with a message when ../shared/data is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}" -LE hw "$@"
