#!/bin/bash
# The live matrix: simulated captures of the named scenes and of random blocks, with both
# simulated devices, each tour turned over halfway, one capture at a time; one table row per
# run (scripts/live-matrix-score.py): scene, device, views, groups, scans in the main group,
# flagged, worst error of the main group's scans against the truth, scans more than 1° or 5 mm
# off without a warning (every group; the goal is 0 everywhere), coverage %, latency
# median / p95 (s).
# Usage: scripts/live-matrix.sh [ANASCAN] [OUT_DIR] [RANDOM_BLOCKS] [VIEWS]
#   MATRIX_SCENES / MATRIX_DEVICES (space separated) override the lists; MATRIX_SEED the tour
#   seed (1); MATRIX_TOUR=footprint walks each block's outline with as many views as it needs
#   (VIEWS is then ignored; default: the fixed circle of VIEWS views). Runs under `nice -n 10`.
set -uo pipefail
ANASCAN=${1:-build/acquisition/anascan}
OUT=${2:-/tmp/live-matrix}
RANDOM_BLOCKS=${3:-10}
VIEWS=${4:-20}
HERE=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
SCENES=${MATRIX_SCENES:-"small-block small-block-turned octagon-block octagon-block-turned large-block large-block-on-side"}
if [ -z "${MATRIX_SCENES:-}" ]; then
    for seed in $(seq 1 "$RANDOM_BLOCKS"); do SCENES="$SCENES random-block:$seed"; done
fi
DEVICES=${MATRIX_DEVICES:-"sim:structured-light sim:tof"}
echo "| scene | device | views | groups | main group | flagged | worst (main group) | wrong without warning | coverage % | latency median / p95 s |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for device in $DEVICES; do
    for scene in $SCENES; do
        name="${device#sim:}-${scene/:/-}"
        rm -rf "${OUT:?}/$name"
        if [ "${MATRIX_TOUR:-fixed}" = footprint ]; then
            tour=(--tour footprint)
        else
            tour=(--views "$VIEWS" --flip-after $((VIEWS / 2)))
        fi
        nice -n 10 "$ANASCAN" --accept-poor capture --device "$device" --scene "$scene" \
            --session "$OUT/$name" "${tour[@]}" \
            --tour-seed "${MATRIX_SEED:-1}" >"$OUT/$name.log" 2>&1
        "$ANASCAN" session info "$OUT/$name" --json >"$OUT/$name.json" 2>>"$OUT/$name.log" &&
            /usr/bin/python3 "$HERE/live-matrix-score.py" "$OUT/$name" "$scene" "$device" \
                <"$OUT/$name.json" || echo "| $scene | $device | (failed: see $OUT/$name.log) |"
    done
done
