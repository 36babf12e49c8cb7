#!/usr/bin/env bash
# Set up, build and run the whole test suite (all labels except `hw`, which needs real
# hardware), then the sanitizer builds of their named sets (scripts/sanitize.sh;
# SANITIZE=0 leaves them out). Tests labelled `data` skip with a message when
# ../shared/data is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}" -LE hw "$@"
if [ "${SANITIZE:-1}" != 0 ]; then bash scripts/sanitize.sh; fi
