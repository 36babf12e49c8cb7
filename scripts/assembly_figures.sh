#!/usr/bin/env bash
# The block-assembly figures of docs/reassembly.md (long: not part of CI), with the
# contact rows along the vertex normals (the default) and along the face planes.
# Usage: scripts/assembly_figures.sh [BUILD_DIR]   (builds anascan_assembly_figures first)
set -euo pipefail
build=${1:-build}
nice -n 10 cmake --build "$build" -j2 --target anascan_assembly_figures
tool="$build/tests/sim/anascan_assembly_figures"
for normal in vertex plane; do
    export NORMAL=$normal
    echo "==== contact normals: $normal"
    echo "== What pulls the wall off the truth: each term at the true poses"
    "$tool" terms 3
    "$tool" terms 4
    echo "== Fig. 15: two neighbours, joint faces without anathyrosis, three monument seeds"
    for seed in 0 7 13; do "$tool" fig15 octagon-wall "$seed"; done
    echo "== Fig. 15 with the simulated anathyrosis"
    "$tool" fig15-anathyrosis
    echo "== 3 and 4 blocks of the wall, 20 random starts 5 deg and 20 mm off"
    "$tool" wall 3 20
    "$tool" wall 4 20
done
