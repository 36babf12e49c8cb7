#!/usr/bin/env bash
# Set up, build and run the whole test suite (all labels except `hw`, which needs real
# hardware). SANITIZE=ci adds the sanitizer set that fits CI's time budget
# (scripts/sanitize.sh ci: ASan + UBSan over the processing library, its unit tests and the
# fuzz corpus replays; docs/reliability.md), SANITIZE=all every set (over CI's budget). The
# default stays none until the ci set has run green on a fresh clone of the merged tree
# within the budget (it ran green on its own tree; docs/reliability.md).
# Tests labelled `data` skip with a message when ../shared/data is absent.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "${JOBS:-$(nproc)}" -LE hw "$@"
case "${SANITIZE:-0}" in
    0) ;;
    ci) bash scripts/sanitize.sh ci ;;
    *) bash scripts/sanitize.sh all ;;
esac
