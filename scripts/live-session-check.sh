#!/bin/sh
# The live-registration figure: a simulated structured-light session of the small
# block, VIEWS views (default 24) turned over halfway, registered by LiveRegistrar as they
# come. Prints per-scan decisions, errors against the truth, add() median/p95 and the
# per-method counts. Usage: scripts/live-session-check.sh [VIEWS] [BUILD_DIR]
set -eu
views=${1:-24}
build=${2:-build}
binary="$build/tests/acquisition/anascan_live_session_sl_tests"
if [ ! -x "$binary" ]; then
    echo "live-session-check: $binary not found (build the target anascan_live_session_sl_tests)" >&2
    exit 2
fi
ANASCAN_LIVE_VIEWS="$views" exec "$binary" --gtest_filter='LiveSessionStructuredLight.*'
