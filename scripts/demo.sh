#!/usr/bin/env bash
# The main job: set up, build, and run a simulated capture session of a stone end to end:
# a structured-light scanner walked around a 0.45 m block (24 views, the stone turned over
# after 12), every scan saved crash-safely and registered live, then the model, the poses
# and the coverage report exported, and the stone's mesh with its model report (see
# docs/capture-session.md and docs/surface-reconstruction.md).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
bash scripts/build.sh >/dev/null

out=build/demo
anascan=./build/acquisition/anascan
rm -rf "$out/session"
mkdir -p "$out"
"$anascan" capture --device sim:structured-light --scene small-block --session "$out/session" \
    --views 24 --flip-after 12
"$anascan" session export "$out/session" --out "$out/model.ply" --poses "$out/poses.conf" \
    --mesh "$out/stone.ply" --resolution-mm 1 --report "$out/stone.json"
"$anascan" coverage "$out/session" --out "$out/coverage.ply" --json > "$out/coverage.json"
"$anascan" coverage "$out/session" 2>/dev/null | head -1
echo "session:         $out/session (anascan session info $out/session)"
echo "model:           $out/model.ply"
echo "poses:           $out/poses.conf"
echo "stone mesh:      $out/stone.ply (orange = interpolated; report $out/stone.json)"
echo "coverage report: $out/coverage.json (coloured samples: $out/coverage.ply)"
