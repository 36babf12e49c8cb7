#!/usr/bin/env bash
# Fragment models of simulated sessions against the true stone (docs/surface-reconstruction.md):
#  - the README's main job (24 views of SCENE, turned over after 12): measured-class
#    accuracy, completeness, closed/manifold/one piece, volume and box against the truth;
#  - 12 views without turning it over: the never-seen area (from the true mesh and the true
#    sensor poses) against the interpolated class.
# Usage: scripts/mesh-truth-check.sh [SCENE] [RESOLUTION_MM] [BUILD_DIR] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
scene="${1:-small-block}"
res="${2:-1}"
build="${3:-build}"
out="${4:-$build/mesh-truth/$scene}"
anascan="$build/acquisition/anascan"
cmake --build "$build" --target anascan >/dev/null
mkdir -p "$out"
"$anascan" sim export-scene "$scene" --stone-only --out "$out/truth.ply" >/dev/null

session() {  # NAME VIEWS FLIP_AFTER
    rm -rf "$out/$1"
    "$anascan" capture --device sim:structured-light --scene "$scene" --session "$out/$1" \
        --views "$2" --flip-after "$3" >"$out/$1-capture.log" 2>&1
    /usr/bin/time -f "whole process: %e s wall, %U s user, %S s system, peak %M kB" \
        "$anascan" session export "$out/$1" --mesh "$out/$1.ply" --resolution-mm "$res" \
        --report "$out/$1.json" --poses "$out/$1-poses.conf" \
        --truth-poses "$out/$1-truth.conf" 2>&1 | grep -v "^info: loaded" >"$out/$1-mesh.log"
    tail -n 1 "$out/$1-mesh.log"
}

echo "== $scene, 24 views turned over after 12, $res mm"
session turned 24 12
"$anascan" mesh eval "$out/turned.ply" --truth "$out/truth.ply" --poses "$out/turned-poses.conf" \
    --truth-poses "$out/turned-truth.conf" --visibility --json "$out/turned-eval.json"
echo "== $scene, 12 views of one side (never turned over), $res mm"
session one-side 12 12
"$anascan" mesh eval "$out/one-side.ply" --truth "$out/truth.ply" \
    --poses "$out/one-side-poses.conf" --truth-poses "$out/one-side-truth.conf" --visibility \
    --json "$out/one-side-eval.json"
