#!/usr/bin/env bash
# Registers the ten Stanford bunny scans after moving each by a random rigid transform
# (seed SEED) and compares the poses with bun.conf's, moved likewise (DIR/truth.conf).
#   scripts/bunny-register-check.sh SEED [BUILD_DIR]
# Writes to /tmp/anascan-bunny-SEED/ (prefix $ANASCAN_BUNNY_OUT): the moved scans (plain x y z points: no normals, no
# sensor position, frames unknown), truth.conf, poses.conf, stats.json. The shared data
# folder is $ANASCAN_SHARED_DATA_DIR (default ../shared/data). Exit status: that of
# `anascan eval --at-centroid` with limits of 0.5 deg and 1 mm (translation measured at each
# scan's centroid: the moved frames' origins lie up to ~0.6 m from the data).
set -euo pipefail
seed=${1:?usage: $0 SEED [BUILD_DIR]}
here=$(cd "$(dirname "$0")/.." && pwd)
build=${2:-$here/build}
anascan=$build/acquisition/anascan
data=${ANASCAN_SHARED_DATA_DIR:-$here/../shared/data}/stanford-bunny-range-scans/data
out=${ANASCAN_BUNNY_OUT:-/tmp/anascan-bunny}-$seed
mkdir -p "$out"
mapfile -t order < <("$anascan" -q sim move-scans "$data/bun.conf" --seed "$seed" --out "$out")
scans=()
for name in "${order[@]}"; do scans+=("$out/$name"); done
start=$(date +%s%N)
"$anascan" register "${scans[@]}" --out "$out/poses.conf" --stats "$out/stats.json"
end=$(date +%s%N)
echo "seed $seed: register wall time $(( (end - start) / 1000000 )) ms"
"$anascan" eval "$out/poses.conf" --truth "$out/truth.conf" \
    --at-centroid --max-rotation-deg 0.5 --max-translation-mm 1
