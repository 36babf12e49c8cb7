#!/usr/bin/env bash
# Runs scripts/bunny-register-check.sh for COUNT seeds from FIRST and prints one line per
# seed (placed scans, max rotation error, max translation error at the centroids, wall time)
# and how many seeds met 0.5 deg / 1 mm with all ten scans placed.
#   scripts/bunny-register-seeds.sh FIRST COUNT [BUILD_DIR]
set -uo pipefail
first=${1:?usage: $0 FIRST COUNT [BUILD_DIR]}
count=${2:?usage: $0 FIRST COUNT [BUILD_DIR]}
here=$(cd "$(dirname "$0")" && pwd)
passed=0
printf '%-10s %-8s %-18s %-20s %s\n' seed placed "max rotation deg" "max translation mm" "register s"
for ((seed = first; seed < first + count; ++seed)); do
    out=$("$here/bunny-register-check.sh" "$seed" "${@:3}" 2>/dev/null)
    status=$?
    summary=$(grep '^placed .* max rotation error' <<<"$out" | tail -1)
    placed=$(sed -E 's/^placed ([0-9]+ of [0-9]+).*/\1/' <<<"$summary")
    rotation=$(sed -E 's/.*max rotation error ([0-9.]+) deg.*/\1/' <<<"$summary")
    translation=$(sed -E 's/.*max translation error ([0-9.]+) mm.*/\1/' <<<"$summary")
    ms=$(sed -nE 's/.*register wall time ([0-9]+) ms.*/\1/p' <<<"$out")
    printf '%-10s %-8s %-18s %-20s %s\n' "$seed" "${placed// of /\/}" "$rotation" "$translation" \
        "$(awk -v ms="${ms:-0}" 'BEGIN { printf "%.2f", ms / 1000 }')"
    [ "$status" -eq 0 ] && passed=$((passed + 1))
done
echo "seeds within 0.5 deg and 1 mm, all scans placed: $passed of $count"
