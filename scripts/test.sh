#!/usr/bin/env bash
# Set up, build and run the whole test suite (all labels except `hw`, which needs real
# hardware). SANITIZE=1 adds the sanitizer builds of their named sets (scripts/sanitize.sh);
# they are not yet part of CI's run: they have not yet run green on a quiet machine within
# CI's time budget (docs/reliability.md). Tests labelled `data` skip with a message when
# ../shared/data is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}" -LE hw "$@"
if [ "${SANITIZE:-0}" = 1 ]; then bash scripts/sanitize.sh; fi
