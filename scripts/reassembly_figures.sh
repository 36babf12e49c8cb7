#!/usr/bin/env bash
# Neighbour-proposal figures of docs/reassembly.md: for octagon-wall with its own seed and
# with further seeds, export the simulated monument, extract block features (from the true
# meshes, optionally with noise), match, and evaluate against the truth; then the ablation
# (each check left out) on the pooled seeds.
# Usage: scripts/reassembly_figures.sh BUILD_DIR WORK_DIR [NOISE_MM] [SEEDS...]
set -euo pipefail
build=${1:?build dir}; work=${2:?work dir}; noise=${3:-0}
shift $(( $# < 3 ? $# : 3 ))
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(0 101 102 103 104 105 106 107 108 109 110)
anascan="$build/acquisition/anascan"
mkdir -p "$work"
for seed in "${seeds[@]}"; do
    d="$work/wall-$seed"
    [ -f "$d/truth.json" ] || "$anascan" -q sim export-monument octagon-wall --seed "$seed" --out "$d" > /dev/null
    [ -d "$d/features" ] || "$anascan" -q blocks features "$d"/blocks/*.ply --out "$d/features" --noise-mm "$noise" > "$d/features.txt"
done
pool() {  # $1: tag, rest: extra match options; prints pooled top-1 / top-3
    local tag=$1; shift
    local t1=0 t3=0 n=0 wrong=0
    for seed in "${seeds[@]}"; do
        d="$work/wall-$seed"
        "$anascan" -q blocks match "$d/features" --out "$d/proposals-$tag.json" "$@" > /dev/null
        read -r f a b w < <("$anascan" -q blocks eval "$d/proposals-$tag.json" --truth "$d/truth.json" --json |
            /usr/bin/python3 -c 'import json,sys; j=json.load(sys.stdin); print(j["joint_faces"], round(j["top1_share"]*j["joint_faces"]), round(j["top3_share"]*j["joint_faces"]), j["wrong_pairs_above_lowest_true"])')
        n=$((n + f)); t1=$((t1 + a)); t3=$((t3 + b)); wrong=$((wrong + w))
    done
    printf "%-16s joint faces %4d  top-1 %5.1f%%  top-3 %5.1f%%  wrong above lowest true (sum) %d\n" \
        "$tag" "$n" "$(echo "100*$t1/$n" | bc -l)" "$(echo "100*$t3/$n" | bc -l)" "$wrong"
}
pool all
for check in neighbours area size roughness nb-roughness edges holes; do pool "no-$check" --disable "$check"; done
