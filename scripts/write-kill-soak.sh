#!/usr/bin/env bash
# Soak test of the writing commands other than `anascan capture` (scripts/capture-kill-soak.sh):
# `anascan session register`, `anascan session export --mesh`, `anascan campaign register` and
# the field app capturing (`anascan-field --capture-views`), each SIGKILLed KILLS times
# (default 50) at random moments spread over an unkilled run. After every kill the session
# passes `session check` with every acknowledged scan (the campaign `campaign check`), each
# output is absent or complete, and the rerun gives the unkilled run's result. Prints one
# line per command (kills, how many landed while it ran, temporaries left).
# Usage: scripts/write-kill-soak.sh [KILLS] [BUILD_DIR] [FILTER]
# FILTER: a GoogleTest filter over WriteKills.*, CampaignKills.* and FieldKills.* (default
# all; FieldKills runs through ctest, which starts the virtual X server).
set -euo pipefail
cd "$(dirname "$0")/.."
kills="${1:-50}"
build="${2:-build}"
filter="${3:-WriteKills.*:CampaignKills.*:FieldKills.*}"
export ANASCAN_WRITE_KILLS="$kills"
cmake --build "$build" --target anascan anascan-field anascan_cli_capture_crash_tests \
    anascan_field_session_tests >/dev/null
status=0
"$build/tests/acquisition/anascan_cli_capture_crash_tests" --gtest_filter="$filter" || status=1
if [[ "$filter" == *FieldKills* ]]; then
    ctest --test-dir "$build" -R '^FieldKills\.' -V --timeout 7200 | grep -E 'anascan-field:|Passed|Failed|Failure' ||
        status=1
fi
exit "$status"
