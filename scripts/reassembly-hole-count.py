#!/usr/bin/env python3
"""Holes found by `blocks features` against the simulated monument's truth, counted per
block and kind (truth.json carries the counts of clamp halves and dowels of each block,
not their positions, so recall and precision are upper bounds).

Usage: scripts/reassembly-hole-count.py WORK_DIR [SEED ...]
WORK_DIR as left by scripts/reassembly_figures.sh (WORK_DIR/wall-SEED/{truth.json,features/}).
"""
import json
import sys
from pathlib import Path


def main() -> int:
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    work = Path(sys.argv[1])
    walls = [work / f"wall-{s}" for s in sys.argv[2:]] or sorted(work.glob("wall-*"))
    kinds = {"clamp channel": "clamp_halves", "dowel": "dowels"}
    true_n = dict.fromkeys(kinds, 0)
    found_n = dict.fromkeys(kinds, 0)
    matched = dict.fromkeys(kinds, 0)
    for wall in walls:
        truth = json.loads((wall / "truth.json").read_text())
        for block in truth["blocks"]:
            path = wall / "features" / f"{block['id']}.features.json"
            if not path.exists():
                print(f"{path}: missing (run blocks features)", file=sys.stderr)
                return 1
            features = json.loads(path.read_text())
            found = dict.fromkeys(kinds, 0)
            for face in features["faces"]:
                for hole in face["holes"]:
                    found[hole["kind"]] += 1
            for kind, key in kinds.items():
                true_n[kind] += block[key]
                found_n[kind] += found[kind]
                matched[kind] += min(block[key], found[kind])
    for kind in kinds:
        recall = 100.0 * matched[kind] / max(true_n[kind], 1)
        precision = 100.0 * matched[kind] / max(found_n[kind], 1)
        print(f"{kind}: {found_n[kind]} found for {true_n[kind]} true in {len(walls)} walls; "
              f"recall at most {recall:.1f} %, precision at most {precision:.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
