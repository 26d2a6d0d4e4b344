#!/usr/bin/python3
"""Sharp features (`clmarch mesh --sharp`) against marching cubes alone, on the rotated box of the
quality tests: how far points on the box's 12 edges (21 a side, corners included) lie from the mesh.

  scripts/mesh-sharp.py [--clmarch build/clmarch] [--resolutions 32 64 128]

For each resolution, with and without --sharp, `clmarch mesh --backend reference --stats` writes a
PLY file, read back here (Debian's python3-numpy); the line gives the triangles, the feature cells,
and the edge points' mean and largest distance from the mesh in cells. docs/meshes.md holds the
results.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

import mesh_ply

HALF = np.array([0.5, 0.3, 0.4])
ROTATE = [10, 20, 30]
SCENE = "sdf: {box: {half_size: [0.5, 0.3, 0.4], rotate: [10, 20, 30]}}\n"


def rotation(degrees):
    """clmarch's world-from-local rotation: about x, then y, then z."""
    x, y, z = (math.radians(d) for d in degrees)
    rx = np.array([[1, 0, 0], [0, math.cos(x), -math.sin(x)], [0, math.sin(x), math.cos(x)]])
    ry = np.array([[math.cos(y), 0, math.sin(y)], [0, 1, 0], [-math.sin(y), 0, math.cos(y)]])
    rz = np.array([[math.cos(z), -math.sin(z), 0], [math.sin(z), math.cos(z), 0], [0, 0, 1]])
    return rz @ ry @ rx


def distance_to_triangles(p, a, b, c):
    """The distance from p to the nearest of the triangles (a[i], b[i], c[i]), by their barycentric
    regions (Ericson, Real-Time Collision Detection, 5.1.5), for all triangles at once."""
    ab, ac, ap, bp, cp = b - a, c - a, p - a, p - b, p - c
    d1, d2 = (ab * ap).sum(1), (ac * ap).sum(1)
    d3, d4 = (ab * bp).sum(1), (ac * bp).sum(1)
    d5, d6 = (ab * cp).sum(1), (ac * cp).sum(1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        total = va + vb + vc
        nearest = a + ab * (vb / total)[:, None] + ac * (vc / total)[:, None]
        on_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        nearest[on_ab] = (a + ab * (d1 / (d1 - d3))[:, None])[on_ab]
        on_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        nearest[on_ac] = (a + ac * (d2 / (d2 - d6))[:, None])[on_ac]
        on_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        nearest[on_bc] = (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[:, None])[on_bc]
    for corner, region in ((a, (d1 <= 0) & (d2 <= 0)), (b, (d3 >= 0) & (d4 <= d3)), (c, (d6 >= 0) & (d5 <= d6))):
        nearest[region] = corner[region]
    return np.sqrt(((nearest - p) ** 2).sum(1)).min()


def edge_points():
    r = rotation(ROTATE)
    for axis in range(3):
        others = [a for a in range(3) if a != axis]
        for s1 in (-1, 1):
            for s2 in (-1, 1):
                for t in np.linspace(-1, 1, 21):
                    q = np.zeros(3)
                    q[axis], q[others[0]], q[others[1]] = t * HALF[axis], s1 * HALF[others[0]], s2 * HALF[others[1]]
                    yield r @ q


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--clmarch", default=os.path.join(os.path.dirname(__file__), "..", "build", "clmarch"))
    parser.add_argument("--resolutions", type=int, nargs="+", default=[32, 64, 128])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "rotated_box.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        print(f"{'N':>5} {'sharp':>6} {'triangles':>10} {'feature_cells':>14} {'mean_cells':>11} {'max_cells':>10}")
        for n in args.resolutions:
            for sharp in (False, True):
                out = os.path.join(tmp, "box.ply")
                command = [args.clmarch, "--quiet", "mesh", scene, "-o", out, "--resolution", str(n), "--stats",
                           "--backend", "reference"] + (["--sharp"] if sharp else [])
                stats = json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)
                vertex, faces = mesh_ply.read_ply(out)
                positions = np.stack([vertex["x"], vertex["y"], vertex["z"]], axis=1).astype(np.float64)
                a, b, c = (positions[faces[:, k].astype(np.int64)] for k in range(3))
                errors = np.array([distance_to_triangles(p, a, b, c) for p in edge_points()]) / stats["cell"]
                print(f"{n:>5} {str(sharp).lower():>6} {stats['triangles']:>10} {stats['feature_cells']:>14} "
                      f"{errors.mean():>11.3f} {errors.max():>10.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
