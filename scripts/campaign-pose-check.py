#!/usr/bin/python3
"""Relative pose errors of an exported campaign against the truth of `anascan sim campaign`.

For every exported stone and every two of its scans that belong to one true stone, compares
T_a^-1 T_b with the truth (rotation angle, and translation at scan b's centre) and prints
the truth stones of its scans and the largest errors. Usage:
    /usr/bin/python3 scripts/campaign-pose-check.py OUT/ SCANS/truth.json
"""
import json
import pathlib
import sys

import numpy as np
import open3d as o3d


def conf_rotation(x, y, z, w):
    # Stanford .conf: p_world = R(q)^T p + t (processing/io/stanford_conf.hpp).
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    return r.T


def read_conf(path):
    poses = []
    for line in open(path):
        f = line.split()
        v = list(map(float, f[2:]))
        T = np.eye(4)
        T[:3, :3] = conf_rotation(*v[3:7])
        T[:3, 3] = v[:3]
        poses.append((f[1], T))
    return poses


def main(out, truth_path):
    truth = {s["file"]: (np.array(s["T_stone_scan"]).reshape(4, 4), s["stone"])
             for s in json.load(open(truth_path))["scans"]}
    for conf in sorted(pathlib.Path(out).glob("stone_*/poses.conf")):
        poses = read_conf(conf)
        worst_deg, worst_mm = 0.0, 0.0
        for a in range(len(poses)):
            for b in range(a):
                (fa, Ta), (fb, Tb) = poses[a], poses[b]
                (Sa, sa), (Sb, sb) = truth[pathlib.Path(fa).name], truth[pathlib.Path(fb).name]
                if sa != sb:
                    continue
                c = np.append(np.asarray(o3d.io.read_point_cloud(fb).points).mean(0), 1.0)
                D = np.linalg.inv(np.linalg.inv(Ta) @ Tb) @ (np.linalg.inv(Sa) @ Sb)
                cos = np.clip((np.trace(D[:3, :3]) - 1) / 2, -1, 1)
                worst_deg = max(worst_deg, np.degrees(np.arccos(cos)))
                worst_mm = max(worst_mm, 1e3 * np.linalg.norm((D @ c - c)[:3]))
        stones = [truth[pathlib.Path(f).name][1] for f, _ in poses]
        print(f"{conf.parent.name}: true stones {stones}: max {worst_deg:.3f} deg, {worst_mm:.3f} mm")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
