#!/usr/bin/python3
"""Side-by-side reliability of global pairwise registration on real partial scans:
`anascan align` (integral-invariant features, forward search, fine registration and
verification) against Open3D's FPFH + RANSAC and FPFH + FGR (fast global registration), each
followed by Open3D point-to-plane ICP (5 mm), on every pair of Stanford bunny scans whose
overlap is at least --min-overlap, each scan moved by a random rigid transform
(`anascan sim move-scans`, uniform rotation, up to 0.5 m).

A result is correct when it is within 0.5 deg and 1 mm (at the source scan's centroid) of
bun.conf. anascan also says whether it accepts a result (exit status 0 = verified); a wrong
result that is accepted is counted. Open3D has no verification step: every result it returns
is its answer. Wall time per pair is measured in this run for each method.

Run with Debian's Python (python3-open3d):
  /usr/bin/python3 tests/bench/bench_pairs_open3d.py --anascan build/acquisition/anascan --seed 1
"""
import argparse
import pathlib
import subprocess
import sys
import time

import numpy as np

from bench_register_open3d import DEFAULT_DATA, VOXEL_M, move_scans, preprocess, ransac

try:
    import open3d as o3d
except ImportError:  # pragma: no cover
    sys.exit("open3d not importable: run with /usr/bin/python3 (Debian python3-open3d)")

reg = o3d.pipelines.registration


def quaternion_to_rotation(x, y, z, w):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def read_conf(path):
    """name -> T_world_scan (4x4) in the .conf convention p_world = R(q)^T p + t."""
    poses = {}
    for line in path.read_text().splitlines():
        fields = line.split()
        if not fields or fields[0] != "bmesh":
            continue
        t = np.array([float(v) for v in fields[2:5]])
        q = [float(v) for v in fields[5:9]]
        T = np.identity(4)
        T[:3, :3] = quaternion_to_rotation(*q).T
        T[:3, 3] = t
        poses[fields[1]] = T
    return poses


def overlap(source, target, T_target_source, distance_m=0.002):
    """Fraction of (1 mm down-sampled) source points within distance_m of the target."""
    moved = source.voxel_down_sample(0.001).transform(T_target_source)
    tree = o3d.geometry.KDTreeFlann(target)
    near = sum(1 for p in moved.points if tree.search_radius_vector_3d(p, distance_m)[0] > 0)
    return near / max(1, len(moved.points))


def error(T, T_true, centroid):
    R = T[:3, :3] @ T_true[:3, :3].T
    angle = np.degrees(np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1)))
    shift = np.linalg.norm((T @ np.append(centroid, 1))[:3] - (T_true @ np.append(centroid, 1))[:3])
    return angle, shift


def anascan_align(anascan, source, target, out):
    xf = out / f"{source.stem}-{target.stem}.xf"
    start = time.perf_counter()
    result = subprocess.run([anascan, "-q", "align", str(source), str(target), "--out", str(xf)],
                            capture_output=True, text=True, check=False)
    elapsed = time.perf_counter() - start
    if result.returncode != 0 or not xf.exists():
        return None, False, elapsed
    return np.loadtxt(xf).reshape(4, 4), True, elapsed


def fgr(source, target):
    return reg.registration_fgr_based_on_feature_matching(
        source[1], target[1], source[2], target[2],
        reg.FastGlobalRegistrationOption(maximum_correspondence_distance=0.5 * VOXEL_M))


def refine(source, target, init):
    return reg.registration_icp(source[0], target[0], 0.005, init,
                                reg.TransformationEstimationPointToPlane()).transformation


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--anascan", required=True)
    parser.add_argument("--data", type=pathlib.Path, default=DEFAULT_DATA)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--min-overlap", type=float, default=0.4)
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("/tmp/anascan-bench-pairs"))
    args = parser.parse_args()
    out = args.out / str(args.seed)
    out.mkdir(parents=True, exist_ok=True)
    scans, truth_path = move_scans(args.anascan, args.data, args.seed, out)
    truth = read_conf(truth_path)
    prepared = {s.name: preprocess(s) for s in scans}
    counts = {m: {"pairs": 0, "correct": 0, "accepted": 0, "wrong_accepted": 0, "time": 0.0}
              for m in ("anascan", "ransac", "fgr")}
    for s in scans:
        for t in scans:
            if s == t:
                continue
            T_true = np.linalg.inv(truth[t.name]) @ truth[s.name]
            source, target = prepared[s.name], prepared[t.name]
            if overlap(source[0], target[0], T_true) < args.min_overlap:
                continue
            centroid = np.asarray(source[0].points).mean(axis=0)
            results = {}
            T, accepted, seconds = anascan_align(args.anascan, s, t, out)
            results["anascan"] = (T, accepted, seconds)
            start = time.perf_counter()
            T = refine(source, target, ransac(source, target).transformation)
            results["ransac"] = (T, True, time.perf_counter() - start)
            start = time.perf_counter()
            T = refine(source, target, fgr(source, target).transformation)
            results["fgr"] = (T, True, time.perf_counter() - start)
            line = f"{s.stem:>9} -> {t.stem:<9}"
            for method, (T, accepted, seconds) in results.items():
                c = counts[method]
                c["pairs"] += 1
                c["time"] += seconds
                good = T is not None and all(
                    a <= b for a, b in zip(error(T, T_true, centroid), (0.5, 0.001)))
                c["correct"] += good and accepted
                c["accepted"] += accepted
                c["wrong_accepted"] += accepted and not good
                line += f"  {method}: {'ok ' if good else 'BAD'}{'' if accepted else ' (rejected)'}"
            print(line, flush=True)
    for method, c in counts.items():
        n = max(1, c["pairs"])
        print(f"{method:>8}: {c['correct']} of {c['pairs']} pairs correct "
              f"({100.0 * c['correct'] / n:.0f} %), {c['accepted']} accepted, "
              f"{c['wrong_accepted']} wrong accepted, mean {c['time'] / n:.2f} s per pair")


if __name__ == "__main__":
    main()
