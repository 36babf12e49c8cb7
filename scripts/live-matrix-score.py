#!/usr/bin/python3
"""One row of the live matrix: a finished simulated capture session scored against its truth.

Reads `anascan session info DIR --json` (stdin) and the session's scan files (their
centroids, where the translation error is measured). Every group is scored, not only the
main one: within a group, the errors are those relative to the group's scan that leaves the
fewest scans off (so a wrong reference scan does not make every other scan look wrong); a
scan is "wrong without a warning" when it is registered (not flagged, not excluded) and more
than 1 degree or 5 mm off. Usage: live-matrix-score.py DIR SCENE DEVICE < info.json
"""
import json
import sys

import numpy as np
import open3d as o3d


def pose(values):
    return np.array(values, dtype=float).reshape(4, 4)


def rotation_deg(R):
    return np.degrees(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0)))


def errors(ref, scans):
    """(rotation deg, translation m) of each scan relative to scan `ref`."""
    out = []
    E0, T0 = pose(ref["pose"]), pose(ref["true_pose"])
    for s in scans:
        Te = np.linalg.inv(E0) @ pose(s["pose"])
        Tt = np.linalg.inv(T0) @ pose(s["true_pose"])
        c = np.append(s["centroid"], 1.0)
        out.append((rotation_deg(Te[:3, :3].T @ Tt[:3, :3]), np.linalg.norm((Te @ c - Tt @ c)[:3])))
    return out


def score_group(scans):
    best = None
    for ref in scans:
        e = errors(ref, scans)
        off = sum(1 for r, t in e if r > 1.0 or t > 0.005)
        if best is None or off < best[0]:
            best = (off, e)
    return best


def main():
    folder, scene, device = sys.argv[1:4]
    d = json.load(sys.stdin)
    scans = d["scans"]
    groups = {}
    for s in scans:
        if s["state"] == "registered" and not s["excluded"] and s["pose"] and s["true_pose"]:
            cloud = o3d.io.read_point_cloud(folder + "/" + s["file"])
            s["centroid"] = np.asarray(cloud.points).mean(axis=0)
            groups.setdefault(s["group"], []).append(s)
    flagged = sum(1 for s in scans if s["state"] == "flagged")
    main_group = max(groups.values(), key=len) if groups else []
    wrong, worst = 0, (0.0, 0.0)
    for members in groups.values():
        off, e = score_group(members)
        wrong += off
        if members is main_group:
            worst = (max(r for r, _ in e), max(t for _, t in e))
    cov = d.get("coverage")  # The covered fraction (older sessions: an object holding it).
    if isinstance(cov, dict):
        cov = cov.get("covered_fraction")
    percent = float(cov) * 100.0 if cov is not None else float("nan")
    lat = sorted(s["latency_s"] for s in scans if s.get("latency_s") is not None)
    med = lat[len(lat) // 2] if lat else float("nan")
    p95 = lat[min(len(lat) - 1, int(0.95 * (len(lat) - 1) + 0.5))] if lat else float("nan")
    print("| %s | %s | %d | %d | %d | %d | %.4f° / %.3f mm | **%d** | %.1f | %.1f / %.1f |"
          % (scene, device, len(scans), len(groups), len(main_group), flagged, worst[0],
             worst[1] * 1e3, wrong, percent, med, p95))


main()
