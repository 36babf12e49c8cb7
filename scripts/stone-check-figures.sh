#!/usr/bin/env bash
# The capture's "another stone?" check over the simulated scenes, both simulated devices and
# several tour seeds (docs/stone-check.md). For each base session (VIEWS views of one stone)
# one more view is captured into a copy of it, from: every other stone (other-stone trials),
# the same stone turned over or on its side, the same stone again (after a pause), and the
# Stanford bunny through the ptx: device (a real scan of another object). Prints one line per
# trial and the table of outcomes.
#
# usage: scripts/stone-check-figures.sh BUILD_DIR [VIEWS] [SEEDS] [DEVICES]
#   e.g. scripts/stone-check-figures.sh build 4 "1 2" "sim:structured-light sim:tof"
# STONES: the base stones (default small-block octagon-block large-block); OTHERS: the other
# stones tried on each base (default: the bases), e.g. OTHERS="random-block:1 random-block:2";
# ADD: the views each trial captures (default 1). With more than one, each trial line also
# says how many of its scans ended in the model (`in-model=N`: of another object, mixed in).
set -u
build=${1:?build dir}
views=${2:-4}
seeds=${3:-"1 2"}
devices=${4:-"sim:structured-light sim:tof"}
cli="$build/acquisition/anascan"
[ -x "$cli" ] || cli="$build/anascan"
[ -x "$cli" ] || { echo "no anascan binary under $build" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bunny=/work/shared/data/stanford-bunny-range-scans/data/bun000.ply
[ -f "${BUNNY:-$bunny}" ] && mkdir -p "$work/bunny" &&
    /usr/bin/python3 "$here/bunny-to-ptx.py" "${BUNNY:-$bunny}" "$work/bunny/bun000.ptx"

stones=${STONES:-"small-block octagon-block large-block"}  # the bases
others=${OTHERS:-$stones}  # the other stones tried on each base
add=${ADD:-1}
turned_of() {
    case $1 in
        large-block) echo large-block-on-side ;;
        *-turned) echo "${1%-turned}" ;;  # A base lying turned over, turned back.
        *) echo "$1-turned" ;;
    esac
}

# The scans after the first VIEWS that ended in the session's largest group.
in_model() {
    "$cli" session info "$1" --json 2>/dev/null | /usr/bin/python3 -c '
import collections, json, sys
scans = json.load(sys.stdin)["scans"]
placed = [s for s in scans if s.get("state") == "registered" and not s.get("excluded")]
sizes = collections.Counter(s["group"] for s in placed)
model = min(sizes, key=lambda g: (-sizes[g], g)) if sizes else None
print(sum(1 for s in placed if s["group"] == model and s["seq"] > int(sys.argv[1])))' "$views"
}

# trial KIND BASE DEVICE SEED -- capture args: prints "KIND outcome"
trial() {
    local kind=$1 base=$2; shift 2
    rm -rf "$work/t"; cp -r "$base" "$work/t"
    local out
    out=$("$cli" capture --session "$work/t" --views $((views + add)) --no-coverage "$@" </dev/null 2>&1)
    local outcome=joined
    if grep -q "another stone?" <<<"$out"; then outcome=asked
    elif grep -q "stone check:.*nothing in its size or surface" <<<"$out"; then outcome=looks-same
    elif grep -q "stone check:.*too few scans" <<<"$out"; then outcome=undecided
    elif ! grep -q "registered scan $((views + 1))" <<<"$out"; then outcome=not-registered
    fi
    grep -o "stone's model.*" <<<"$out" | head -1 | sed 's/^/    # /' >&2
    if [ "$add" -gt 1 ]; then
        local asked_at
        asked_at=$(grep -o "another stone? scan [0-9]*" <<<"$out" | head -1 | grep -o "[0-9]*$")
        echo "$kind $outcome${asked_at:+ at=$asked_at} in-model=$(in_model "$work/t")"
    else
        echo "$kind $outcome"
    fi
}

for device in $devices; do
    for stone in $stones; do
        for seed in $seeds; do
            base="$work/base-$seed"; rm -rf "$base"
            "$cli" capture --device "$device" --scene "$stone" --session "$base" --views "$views" \
                --flip-after 0 --tour-seed "$seed" --no-coverage </dev/null >/dev/null 2>&1
            model=$("$cli" session info "$base" --json 2>/dev/null | /usr/bin/python3 -c \
                'import json,sys; s=json.load(sys.stdin)["scans"]; print(sum(1 for x in s if x.get("state")=="registered"))' 2>/dev/null)
            tag="$device $stone seed=$seed model=$model"
            for other in $others; do
                [ "$other" = "$stone" ] && continue
                echo "$tag other:$other $(trial other "$base" --device "$device" --scene "$other" --tour-seed "$seed" --flip-after 0)"
            done
            echo "$tag turned:$(turned_of $stone) $(trial same "$base" --device "$device" --scene "$(turned_of $stone)" --tour-seed "$seed" --flip-after 0)"
            echo "$tag again:$stone $(trial same "$base" --device "$device" --scene "$stone" --tour-seed "$seed" --flip-after 0)"
            [ -d "$work/bunny" ] &&
                echo "$tag bunny:ptx $(trial other "$base" --device "ptx:$work/bunny")"
        done
    done
done | tee "$work/lines"
echo
echo "device kind trials asked looks-same undecided joined not-registered"
sed -E 's/ (at|in-model)=[0-9]+//g' "$work/lines" | awk '{kind=$(NF-1); dev=$1; k=dev" "kind; n[k]++; c[k" "$NF]++}
     END {for (k in n) printf "%s %d %d %d %d %d %d\n", k, n[k], c[k" asked"], c[k" looks-same"],
          c[k" undecided"], c[k" joined"], c[k" not-registered"]}' | sort
