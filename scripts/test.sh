#!/usr/bin/env bash
# Set up, build and run the whole test suite (all labels except `hw`, which needs real
# hardware), then the sanitizer sets that fit CI's time budget (SANITIZE=ci, the default:
# scripts/sanitize.sh ci, ASan + UBSan over the processing library, its unit tests and the
# fuzz corpus replays, and ThreadSanitizer over everything that runs threads of its own;
# docs/reliability.md). SANITIZE=all adds the whole ASan set (over CI's budget), SANITIZE=0
# runs none.
# Tests labelled `data` skip with a message when ../shared/data is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}" -LE hw "$@"
case "${SANITIZE:-ci}" in
    0) ;;
    ci) bash scripts/sanitize.sh ci ;;
    *) bash scripts/sanitize.sh all ;;
esac
