#!/bin/bash
# The live sessions of the group consistency check: for each scene, one simulated
# structured-light capture, then `anascan session info --json` scored against the truth:
# groups, scans of the model, flagged scans, and the scans of the model more than 1° or 5 mm
# from the truth without a warning (the goal is zero).
# Usage: scripts/consistency-figures.sh [ANASCAN] [OUT_DIR]
set -euo pipefail
ANASCAN=${1:-build/acquisition/anascan}
OUT=${2:-/tmp/consistency-figures}
mkdir -p "$OUT"
run() {
    local name=$1
    shift
    rm -rf "$OUT/$name"
    "$ANASCAN" --accept-poor capture --device sim:structured-light --session "$OUT/$name" "$@" \
        >"$OUT/$name.log" 2>&1 || true
    "$ANASCAN" session info "$OUT/$name" --json | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)
states = {}
groups = set()
for s in d["scans"]:
    states[s["state"]] = states.get(s["state"], 0) + 1
    if s["state"] == "registered":
        groups.add(s["group"])
t = d.get("truth") or {}
print("%-22s scans %2d  groups %2d  states %s  model %s  worst %.2f deg / %.1f mm  off>1deg/5mm without warning: %s"
      % (sys.argv[1], len(d["scans"]), len(groups), states, t.get("model_scans"),
         t.get("max_rotation_deg", float("nan")), 1e3 * t.get("max_translation_m", float("nan")),
         t.get("off_1deg_5mm")))
' "$name"
}
run small-block-turned --scene small-block-turned --views 4
run small-block --scene small-block --views 24 --flip-after 12
run octagon-block --scene octagon-block --views 24 --flip-after 12
run large-block-on-side --scene large-block-on-side --views 24 --flip-after 12
