#!/usr/bin/python3
"""Marching cubes against marching tetrahedra (`clmarch mesh --cells`) on scenes with closed forms.

  scripts/mesh-cells.py [--clmarch build/clmarch] [--resolutions 128 256] [--backend reference|opencl]

For each scene (the quality tests' sphere, rotated box, torus, capsule and two disjoint spheres),
resolution and cell method: `clmarch mesh --precision double --stats` writes a PLY file, read back
here (Debian's python3-numpy), and the line says its triangles, the wall time clmarch reports
(total_ms), the worst distance of a vertex from the surface in cells (the scene's field at the
vertices by `clmarch field --backend reference`, in double), the enclosed volume's error against
the closed form, the Euler characteristic and the open edges (directed edges without their
reverse, or in two triangles). docs/meshes.md holds the results.
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

PI = math.pi
SCENES = [
    ("sphere", "sphere: {center: [0.3, -0.2, 0.1], radius: 1}", 4 / 3 * PI, 2),
    ("rotated_box", "box: {half_size: [0.5, 0.3, 0.4], rotate: [10, 20, 30]}", 8 * 0.5 * 0.3 * 0.4, 2),
    ("torus", "torus: {major_radius: 1, minor_radius: 0.3}", 2 * PI * PI * 0.09, 0),
    ("capsule", "capsule: {a: [-0.4, -0.3, 0.1], b: [0.5, 0.4, -0.2], radius: 0.3}",
     PI * 0.09 * math.sqrt(0.81 + 0.49 + 0.09) + 4 / 3 * PI * 0.027, 2),
    ("disjoint", "union: [{sphere: {center: [-1, 0, 0], radius: 0.5}}, {sphere: {center: [1, 0.2, 0], radius: 0.5}}]",
     2 * 4 / 3 * PI * 0.125, 4),
]


def read_ply(path):
    vertex, faces = mesh_ply.read_ply(path)
    return np.stack([vertex["x"], vertex["y"], vertex["z"]], axis=1), faces.astype(np.int64)


def topology(vertices, faces):
    a, b = faces.reshape(-1), np.roll(faces, -1, axis=1).reshape(-1)
    directed = a * len(vertices) + b
    unique, counts = np.unique(directed, return_counts=True)
    reverse = b * len(vertices) + a
    has_reverse = np.isin(reverse, unique)
    open_edges = int(np.count_nonzero(counts > 1) + np.count_nonzero(~has_reverse))
    edges = len(np.unique(np.minimum(a, b) * len(vertices) + np.maximum(a, b)))
    used = len(np.unique(faces))
    return used - edges + len(faces), open_edges


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--clmarch", default="build/clmarch")
    parser.add_argument("--resolutions", type=int, nargs="+", default=[128, 256])
    parser.add_argument("--backend", default="reference", choices=["reference", "opencl"])
    args = parser.parse_args()
    print(f"{'scene':12} {'N':>5} {'cells':>10} {'triangles':>10} {'ms':>8} {'worst/h':>9} {'volume':>9} "
          f"{'euler':>6} {'open':>5}")
    with tempfile.TemporaryDirectory() as tmp:
        for name, sdf, volume, euler in SCENES:
            scene = os.path.join(tmp, name + ".yaml")
            with open(scene, "w") as f:
                f.write("sdf: {" + sdf + "}\n")
            for n in args.resolutions:
                for cells in ("cubes", "tetrahedra"):
                    out = os.path.join(tmp, "mesh.ply")
                    run = subprocess.run([args.clmarch, "--quiet", "mesh", scene, "-o", out, "--resolution", str(n),
                                          "--cells", cells, "--precision", "double", "--backend", args.backend,
                                          "--stats"], check=True, capture_output=True, text=True)
                    stats = json.loads(run.stdout)
                    vertices, faces = read_ply(out)
                    points = os.path.join(tmp, "points.csv")
                    np.savetxt(points, vertices, delimiter=",", header="x,y,z", comments="", fmt="%.17g")
                    field = os.path.join(tmp, "field.csv")
                    subprocess.run([args.clmarch, "--quiet", "field", scene, "--points", points, "-o", field,
                                    "--backend", "reference"], check=True)
                    distance = np.loadtxt(field, delimiter=",", skiprows=1, usecols=3)
                    a, b, c = (vertices[faces[:, k]] for k in range(3))
                    enclosed = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
                    chi, open_edges = topology(vertices, faces)
                    print(f"{name:12} {n:>5} {cells:>10} {len(faces):>10} {stats['total_ms']:>8.0f} "
                          f"{np.abs(distance).max() / stats['cell']:>9.1e} {enclosed / volume - 1:>+9.2e} "
                          f"{chi:>6}{'' if chi == euler else '!':1} {open_edges:>4}")
                    sys.stdout.flush()


if __name__ == "__main__":
    main()
