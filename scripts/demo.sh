#!/usr/bin/env bash
# The main job: set up, build, and run the end-to-end example. Uses the Stanford bunny
# range scans in ../shared/data when present, else simulated scans of a stone block.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build.sh >/dev/null

bunny="../shared/data/stanford-bunny-range-scans/data"
args=(demo --out build/demo)
if [ -f "$bunny/bun.conf" ]; then args+=(--bunny "$bunny"); fi
./build/acquisition/anascan "${args[@]}"
