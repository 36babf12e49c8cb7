#!/usr/bin/env bash
# Soak test of crash safety: `anascan capture` SIGKILLed KILLS times (default 500) at
# random moments in one session; after each kill `session check --repair` must succeed and
# every acknowledged scan must load. Usage: scripts/capture-kill-soak.sh [KILLS] [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
kills="${1:-500}"
build="${2:-build}"
cmake --build "$build" --target anascan anascan_cli_capture_crash_tests >/dev/null
ANASCAN_KILLS="$kills" "$build/tests/acquisition/anascan_cli_capture_crash_tests"
