#!/usr/bin/env python3
"""Writes a Stanford bunny range scan (ASCII PLY) as a one-row PTX station file, so that a
capture can take it through the `ptx:` device as a real scan of another object.

usage: bunny-to-ptx.py BUN.ply OUT.ptx

The scanner is put 1 m along +z of the scan's frame (the range scanner looked along -z):
the points are written relative to it (metres), with the scanner at the PTX origin."""
import sys


def vertices(path):
    with open(path) as f:
        count = 0
        for line in f:
            if line.startswith("element vertex"):
                count = int(line.split()[2])
            if line.strip() == "end_header":
                break
        for _ in range(count):
            x, y, z = line_xyz(next(f))
            yield x, y, z


def line_xyz(line):
    parts = line.split()
    return float(parts[0]), float(parts[1]), float(parts[2])


def main():
    points = list(vertices(sys.argv[1]))
    with open(sys.argv[2], "w") as out:
        out.write(f"{len(points)}\n1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n")
        out.write("1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n")
        for x, y, z in points:
            out.write(f"{x:.6f} {y:.6f} {z - 1.0:.6f} 0.5\n")


if __name__ == "__main__":
    main()
