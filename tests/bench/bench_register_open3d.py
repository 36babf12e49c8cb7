#!/usr/bin/python3
"""Side-by-side benchmark of unordered scan registration: `anascan register` against Open3D's
documented pipeline (FPFH + RANSAC global registration of every pair, point-to-plane ICP,
pose graph, global optimisation; the "Global registration" and "Multiway registration"
tutorials), on the ten Stanford bunny scans moved by random rigid transforms (uniform
rotation, up to 0.5 m translation, shuffled order; `anascan sim move-scans`).

Both results are written as .conf files and judged by `anascan eval --at-centroid` against
bun.conf moved likewise (rotation error in degrees, translation error in mm at each scan's
centroid, in the frame of the first common scan). Wall time of each side is measured in this
run, from the PLY files to the poses, and reported as a ratio.

Run with Debian's Python (python3-open3d):
  /usr/bin/python3 tests/bench/bench_register_open3d.py --anascan build/acquisition/anascan \
      --seeds 1 2 3
"""
import argparse
import pathlib
import re
import subprocess
import sys
import time

import numpy as np

try:
    import open3d as o3d
except ImportError:  # pragma: no cover - environment problem, say what to do
    sys.exit("open3d not importable: run with /usr/bin/python3 (Debian python3-open3d)")

HERE = pathlib.Path(__file__).resolve().parent
DEFAULT_DATA = HERE.parents[2] / "shared/data/stanford-bunny-range-scans/data"


def run(command):
    return subprocess.run(command, check=False, capture_output=True, text=True)


def move_scans(anascan, data, seed, out):
    """The moved scans in shuffled order (paths) and the truth .conf."""
    result = run([anascan, "-q", "sim", "move-scans", str(data / "bun.conf"), "--seed",
                  str(seed), "--out", str(out)])
    if result.returncode != 0:
        sys.exit(f"anascan sim move-scans failed: {result.stderr}")
    return [out / name for name in result.stdout.split()], out / "truth.conf"


def evaluate(anascan, poses, truth):
    """(placed, scans, max rotation deg, max translation mm) from anascan eval."""
    result = run([anascan, "eval", str(poses), "--truth", str(truth), "--at-centroid"])
    match = re.search(r"placed (\d+) of (\d+); max rotation error ([0-9.]+) deg, "
                      r"max translation error ([0-9.]+) mm", result.stdout)
    if not match:
        return (0, 0, float("nan"), float("nan"))
    return (int(match[1]), int(match[2]), float(match[3]), float(match[4]))


def register_anascan(anascan, scans, out):
    poses = out / "anascan.conf"
    start = time.perf_counter()
    result = run([anascan, "-q", "register", *map(str, scans), "--out", str(poses)])
    elapsed = time.perf_counter() - start
    if result.returncode != 0:
        print(f"anascan register failed: {result.stderr.strip()}")
    return poses, elapsed


# --- Open3D, following its tutorials (parameters scaled to a 0.15 m object) -------------
VOXEL_M = 0.002  # Down-sampling for features and RANSAC (~5k points per bunny scan).


def preprocess(path):
    cloud = o3d.io.read_point_cloud(str(path))
    down = cloud.voxel_down_sample(VOXEL_M)
    down.estimate_normals(o3d.geometry.KDTreeSearchParamHybrid(radius=2 * VOXEL_M, max_nn=30))
    fpfh = o3d.pipelines.registration.compute_fpfh_feature(
        down, o3d.geometry.KDTreeSearchParamHybrid(radius=5 * VOXEL_M, max_nn=100))
    if not cloud.has_normals():
        cloud.estimate_normals(o3d.geometry.KDTreeSearchParamKNN(15))
    return cloud, down, fpfh


def ransac(source, target):
    reg = o3d.pipelines.registration
    distance = 1.5 * VOXEL_M
    return reg.registration_ransac_based_on_feature_matching(
        source[1], target[1], source[2], target[2], True, distance,
        reg.TransformationEstimationPointToPoint(False), 3,
        [reg.CorrespondenceCheckerBasedOnEdgeLength(0.9),
         reg.CorrespondenceCheckerBasedOnDistance(distance)],
        reg.RANSACConvergenceCriteria(100000, 0.999))


def icp(source, target, init):
    reg = o3d.pipelines.registration
    result = reg.registration_icp(source[0], target[0], 0.005, init,
                                  reg.TransformationEstimationPointToPlane())
    information = reg.get_information_matrix_from_point_clouds(
        source[0], target[0], 0.005, result.transformation)
    return result, information


def register_pairs(prepared):
    """RANSAC + ICP for every pair s < t: {(s, t): (T_t_s, information, fitness)}."""
    pairs = {}
    for s in range(len(prepared)):
        for t in range(s + 1, len(prepared)):
            coarse = ransac(prepared[s], prepared[t])
            fine, information = icp(prepared[s], prepared[t], coarse.transformation)
            pairs[(s, t)] = (fine.transformation, information, fine.fitness)
    return pairs


def chain_graph(n, pairs):
    """The tutorial's graph: odometry edges between consecutive files, the rest uncertain."""
    reg = o3d.pipelines.registration
    graph = reg.PoseGraph()
    odometry = np.identity(4)
    graph.nodes.append(reg.PoseGraphNode(odometry))
    for (s, t), (T, information, _) in sorted(pairs.items()):
        if t == s + 1:
            odometry = T @ odometry
            graph.nodes.append(reg.PoseGraphNode(np.linalg.inv(odometry)))
        graph.edges.append(reg.PoseGraphEdge(s, t, T, information, uncertain=t != s + 1))
    return graph


def tree_graph(n, pairs):
    """A fairer start for shuffled scans: node poses along a maximum spanning tree of the
    pairs by ICP fitness (tree edges certain, the others uncertain)."""
    reg = o3d.pipelines.registration
    parent = list(range(n))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    tree = []
    for (s, t), (_, _, fitness) in sorted(pairs.items(), key=lambda kv: -kv[1][2]):
        if root(s) != root(t):
            parent[root(s)] = root(t)
            tree.append((s, t))
    poses = {0: np.identity(4)}  # T_world_scan
    while len(poses) < n:
        grown = False
        for s, t in tree:
            T_t_s = pairs[(s, t)][0]
            if t in poses and s not in poses:
                poses[s], grown = poses[t] @ T_t_s, True
            elif s in poses and t not in poses:
                poses[t], grown = poses[s] @ np.linalg.inv(T_t_s), True
        if not grown:
            break
    graph = reg.PoseGraph()
    for i in range(n):
        graph.nodes.append(reg.PoseGraphNode(poses.get(i, np.identity(4))))
    for (s, t), (T, information, _) in sorted(pairs.items()):
        graph.edges.append(reg.PoseGraphEdge(s, t, T, information, uncertain=(s, t) not in tree))
    return graph


def optimise(graph):
    reg = o3d.pipelines.registration
    reg.global_optimization(
        graph, reg.GlobalOptimizationLevenbergMarquardt(),
        reg.GlobalOptimizationConvergenceCriteria(),
        reg.GlobalOptimizationOption(max_correspondence_distance=0.005,
                                     edge_prune_threshold=0.25, reference_node=0))
    return [node.pose for node in graph.nodes]


def register_open3d(scans, out):
    """Multiway registration: every pair by RANSAC + ICP, a pose graph, global optimisation;
    with the tutorial's odometry chain (file order) and with a spanning-tree start.
    Returns [(name, poses path, seconds)]."""
    start = time.perf_counter()
    prepared = [preprocess(path) for path in scans]
    pairs = register_pairs(prepared)
    shared_s = time.perf_counter() - start
    results = []
    for name, build in (("open3d", chain_graph), ("open3d-tree", tree_graph)):
        start = time.perf_counter()
        matrices = optimise(build(len(scans), pairs))
        seconds = shared_s + time.perf_counter() - start
        poses = out / f"{name}.conf"
        write_conf(poses, scans, matrices)
        results.append((name, poses, seconds))
    return results


def write_conf(path, scans, matrices):
    """bmesh lines of T_world_scan: translation t and the quaternion q (x y z w) with
    R(q) = R^T (the .conf convention: p_world = R(q)^T p + t; see io/stanford_conf.hpp)."""
    lines = []
    for scan, T in zip(scans, matrices):
        q = rotation_to_quaternion(T[:3, :3].T)
        t = T[:3, 3]
        lines.append(f"bmesh {scan.name} {t[0]:.9f} {t[1]:.9f} {t[2]:.9f} "
                     f"{q[0]:.9f} {q[1]:.9f} {q[2]:.9f} {q[3]:.9f}")
    path.write_text("\n".join(lines) + "\n")


def rotation_to_quaternion(R):
    """(x, y, z, w) of a rotation matrix (Shepperd's method)."""
    w = np.sqrt(max(0.0, 1.0 + R[0, 0] + R[1, 1] + R[2, 2])) / 2.0
    x = np.sqrt(max(0.0, 1.0 + R[0, 0] - R[1, 1] - R[2, 2])) / 2.0
    y = np.sqrt(max(0.0, 1.0 - R[0, 0] + R[1, 1] - R[2, 2])) / 2.0
    z = np.sqrt(max(0.0, 1.0 - R[0, 0] - R[1, 1] + R[2, 2])) / 2.0
    x = np.copysign(x, R[2, 1] - R[1, 2])
    y = np.copysign(y, R[0, 2] - R[2, 0])
    z = np.copysign(z, R[1, 0] - R[0, 1])
    return np.array([x, y, z, w]) / np.linalg.norm([x, y, z, w])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--anascan", required=True, help="path of the anascan executable")
    parser.add_argument("--data", type=pathlib.Path, default=DEFAULT_DATA,
                        help="folder with bun.conf and the bunny scans")
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("/tmp/anascan-bench-register"))
    args = parser.parse_args()
    if not (args.data / "bun.conf").exists():
        sys.exit(f"bunny scans not found at {args.data}")
    print(f"{'seed':>5} {'side':>12} {'placed':>7} {'max rot deg':>12} {'max trans mm':>13} "
          f"{'time s':>8}")
    ratios = []
    for seed in args.seeds:
        out = args.out / str(seed)
        out.mkdir(parents=True, exist_ok=True)
        scans, truth = move_scans(args.anascan, args.data, seed, out)
        ours, ours_s = register_anascan(args.anascan, scans, out)
        theirs = register_open3d(scans, out)
        for side, poses, seconds in [("anascan", ours, ours_s)] + theirs:
            placed, total, rot, trans = evaluate(args.anascan, poses, truth)
            print(f"{seed:>5} {side:>12} {placed:>3}/{total:<3} {rot:>12.3f} {trans:>13.3f} "
                  f"{seconds:>8.2f}")
        ratios.append(theirs[0][2] / ours_s)
        print(f"{seed:>5} speed-up (open3d time / anascan time): {ratios[-1]:.1f}x", flush=True)
    print(f"median speed-up over {len(ratios)} seeds: {np.median(ratios):.1f}x")


if __name__ == "__main__":
    main()
