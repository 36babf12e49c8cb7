#!/usr/bin/env bash
# Soak test of the writing commands other than capture: `anascan session register`,
# `anascan session export --mesh` and `anascan campaign register` each SIGKILLed KILLS times
# (default 50) at random moments spread over an unkilled run; after every kill the session
# passes `session check` with every acknowledged scan (the campaign `campaign check`), each
# output is absent or complete, and the rerun gives the unkilled run's result. Prints one
# line per command (kills, how many landed while it ran, temporaries left).
# Usage: scripts/write-kill-soak.sh [KILLS] [BUILD_DIR] [FILTER]
# (FILTER: a GoogleTest filter, e.g. 'CampaignKills.*'; default all three).
set -euo pipefail
cd "$(dirname "$0")/.."
kills="${1:-50}"
build="${2:-build}"
filter="${3:-WriteKills.*:CampaignKills.*}"
cmake --build "$build" --target anascan anascan_cli_capture_crash_tests >/dev/null
ANASCAN_WRITE_KILLS="$kills" "$build/tests/acquisition/anascan_cli_capture_crash_tests" \
    --gtest_filter="$filter"
