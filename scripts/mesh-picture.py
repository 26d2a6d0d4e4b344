#!/usr/bin/python3
"""Renders a binary PLY mesh to a PNG picture with POV-Ray, headless (docs/meshes.md's pictures).

  scripts/mesh-picture.py MESH.ply OUT.png --camera X,Y,Z --look-at X,Y,Z [--fov DEGREES]
                          [--size 800x600] [--flat] [--edges] [--color R,G,B]

The mesh is read here (Debian's python3-numpy) and written as a POV-Ray mesh2: its vertices, its
normals (smooth shading; --flat leaves them out, so every triangle shows), its per-vertex colours
(sRGB bytes, linearised; --color gives one colour instead), its triangles. --edges draws every
edge as a thin dark cylinder (for meshes of some thousands of triangles). Lit by a key light at
the camera's upper left, a fill light and a sky-coloured ambient; white background. Needs
`povray` (scripts/setup.sh --povray).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

from mesh_ply import read_ply



def vec(text):
    values = [float(v) for v in text.split(",")]
    if len(values) != 3:
        raise argparse.ArgumentTypeError(f"expected X,Y,Z (got {text})")
    return values


def srgb_to_linear(byte):
    c = byte / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def pov_vectors(rows):
    return ",\n".join(f"<{a:.7g},{b:.7g},{c:.7g}>" for a, b, c in rows)


def write_scene(f, vertex, faces, args):
    x, y, z = vertex["x"], vertex["y"], vertex["z"]
    # POV-Ray is left-handed: z negated keeps the mesh's handedness and its triangles' winding.
    positions = np.stack([x, y, -z], axis=1)
    cam, look = np.array(args.camera), np.array(args.look_at)
    cam[2], look[2] = -cam[2], -look[2]
    width, height = args.size
    f.write("#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\nbackground { rgb 1 }\n")
    f.write(f"camera {{ perspective location <{cam[0]},{cam[1]},{cam[2]}> look_at <{look[0]},{look[1]},{look[2]}> "
            f"right x*{width / height} angle {args.fov * width / height} }}\n")
    forward = look - cam
    forward /= np.linalg.norm(forward)
    side = np.cross([0.0, 1.0, 0.0], forward)
    key = cam + 3 * np.linalg.norm(look - cam) * (0.6 * np.array([0.0, 1.0, 0.0]) - 0.5 * side)
    f.write(f"light_source {{ <{key[0]},{key[1]},{key[2]}> rgb 0.9 }}\n")
    fill = cam + 2 * np.linalg.norm(look - cam) * (0.8 * side + 0.2 * np.array([0.0, 1.0, 0.0]))
    f.write(f"light_source {{ <{fill[0]},{fill[1]},{fill[2]}> rgb 0.35 shadowless }}\n")
    f.write("#default { finish { ambient 0.18 diffuse 0.75 specular 0.15 roughness 0.05 } }\n")
    f.write("mesh2 {\n vertex_vectors { %d,\n%s }\n" % (len(positions), pov_vectors(positions)))
    if not args.flat and "nx" in vertex.dtype.names:
        normals = np.stack([vertex["nx"], vertex["ny"], -vertex["nz"]], axis=1)
        f.write(" normal_vectors { %d,\n%s }\n" % (len(normals), pov_vectors(normals)))
    per_vertex = args.color is None and "red" in vertex.dtype.names
    if per_vertex:
        rgb = np.stack([srgb_to_linear(vertex[c].astype(float)) for c in ("red", "green", "blue")], axis=1)
        palette, index = np.unique(np.round(rgb, 3), axis=0, return_inverse=True)
        index = index.reshape(-1)
        f.write(" texture_list { %d,\n%s }\n" % (
            len(palette), "\n".join(f"texture {{ pigment {{ rgb <{r},{g},{b}> }} }}" for r, g, b in palette)))
    f.write(" face_indices { %d,\n" % len(faces))
    if per_vertex:
        f.write(",\n".join(f"<{a},{b},{c}>,{index[a]},{index[b]},{index[c]}" for a, b, c in faces))
    else:
        f.write(",\n".join(f"<{a},{b},{c}>" for a, b, c in faces))
    color = args.color or [0.8, 0.8, 0.8]
    f.write(f" }}\n texture {{ pigment {{ rgb <{color[0]},{color[1]},{color[2]}> }} }}\n}}\n")
    if args.edges:
        pairs = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
        pairs = np.unique(np.sort(pairs, axis=1), axis=0)
        radius = 0.0012 * np.linalg.norm(positions.max(axis=0) - positions.min(axis=0))
        f.write("union {\n")
        for a, b in pairs:
            p, q = positions[a], positions[b]
            if np.linalg.norm(q - p) < 1e-3 * radius:
                continue  # two vertices at one grid point: no edge to draw
            f.write(f"cylinder {{ <{p[0]:.6g},{p[1]:.6g},{p[2]:.6g}>, <{q[0]:.6g},{q[1]:.6g},{q[2]:.6g}>, {radius:.4g} }}\n")
        f.write(" pigment { rgb 0.05 } finish { ambient 0 diffuse 0.3 }\n}\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh")
    parser.add_argument("out")
    parser.add_argument("--camera", type=vec, required=True)
    parser.add_argument("--look-at", type=vec, required=True)
    parser.add_argument("--fov", type=float, default=45.0, help="vertical field of view, degrees")
    parser.add_argument("--size", type=lambda s: tuple(int(v) for v in s.split("x")), default=(800, 600))
    parser.add_argument("--flat", action="store_true")
    parser.add_argument("--edges", action="store_true")
    parser.add_argument("--color", type=vec)
    args = parser.parse_args()
    vertex, faces = read_ply(args.mesh)
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "mesh.pov")
        with open(scene, "w") as f:
            write_scene(f, vertex, faces, args)
        width, height = args.size
        run = subprocess.run(["povray", "-D", "+A0.1", f"+W{width}", f"+H{height}", f"+I{scene}",
                              f"+O{os.path.abspath(args.out)}", "Output_File_Type=N", "Display_Gamma=sRGB",
                              "File_Gamma=sRGB"], capture_output=True, text=True, cwd=tmp)
        if run.returncode != 0:
            sys.exit(f"mesh-picture.py: povray failed: {run.stderr[-2000:]}")


if __name__ == "__main__":
    main()
