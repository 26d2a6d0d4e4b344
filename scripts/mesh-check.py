#!/usr/bin/python3
"""Counts the triangles and the non-manifold edges of a binary little-endian PLY mesh, read here
independently of clmarch's writer (scripts/mesh-vs-mandelbulber.sh checks both meshes with it).

  scripts/mesh-check.py MESH.ply [--json]     (Debian's python3 and python3-numpy: scripts/setup.sh)

Edges are taken by vertex index (the mesh as written, not welded by position). Printed:
  vertices, triangles
  boundary     edges in one triangle only (a hole)
  overshared   edges in three or more triangles
  misoriented  edges in two triangles that run it the same way (the two disagree on the outside)
  nonmanifold  boundary + overshared + misoriented: 0 for a closed, consistently oriented mesh
  degenerate   triangles that repeat a vertex index
  bad_index    triangles with an index past the vertices (left out of the edge counts)
Exit 0 when the file was read, 2 when it is no binary little-endian triangle PLY.
"""
import argparse
import json
import sys

import numpy as np

PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1",
    "short": "<i2", "int16": "<i2", "ushort": "<u2", "uint16": "<u2",
    "int": "<i4", "int32": "<i4", "uint": "<u4", "uint32": "<u4",
    "float": "<f4", "float32": "<f4", "double": "<f8", "float64": "<f8",
}


def fail(message):
    print(f"mesh-check.py: {message}", file=sys.stderr)
    sys.exit(2)


def read_header(f, path):
    if f.readline().strip() != b"ply":
        fail(f"{path}: not a PLY file")
    elements = []  # (name, count, [(property, dtype)] or ("list", count dtype, index dtype))
    while True:
        line = f.readline()
        if not line:
            fail(f"{path}: the header has no end_header")
        words = line.decode("ascii", "replace").split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "format" and words[1] != "binary_little_endian":
            fail(f"{path}: format {words[1]}: only binary_little_endian is read")
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property":
            if words[1] == "list":
                elements[-1][2].append(("list", PLY_TYPES[words[2]], PLY_TYPES[words[3]]))
            else:
                elements[-1][2].append((words[2], PLY_TYPES[words[1]]))
        elif words[0] == "end_header":
            return elements


def read_triangles(path):
    with open(path, "rb") as f:
        elements = read_header(f, path)
        vertices, triangles = 0, None
        for name, count, properties in elements:
            if name == "face":
                if len(properties) != 1 or properties[0][0] != "list":
                    fail(f"{path}: element face must hold one list property")
                _, count_type, index_type = properties[0]
                record = np.dtype([("n", count_type), ("i", index_type, 3)])
                faces = np.fromfile(f, dtype=record, count=count)
                if len(faces) != count:
                    fail(f"{path}: {len(faces)} of {count} faces in the file")
                if np.any(faces["n"] != 3):
                    fail(f"{path}: a face is not a triangle (faces of mixed sizes are not read)")
                triangles = faces["i"].astype(np.int64)
            else:
                if any(p[0] == "list" for p in properties):
                    fail(f"{path}: element {name} holds a list")
                record = np.dtype([(p[0], p[1]) for p in properties])
                f.seek(record.itemsize * count, 1)
                if name == "vertex":
                    vertices = count
        if triangles is None:
            fail(f"{path}: no face element")
        return vertices, triangles


def edge_counts(vertices, triangles):
    valid = np.all((triangles >= 0) & (triangles < vertices), axis=1)
    bad_index = int(len(triangles) - np.count_nonzero(valid))
    triangles = triangles[valid]
    degenerate = int(np.count_nonzero((triangles[:, 0] == triangles[:, 1]) | (triangles[:, 1] == triangles[:, 2])
                                      | (triangles[:, 2] == triangles[:, 0])))
    a = triangles.reshape(-1)
    b = np.roll(triangles, -1, axis=1).reshape(-1)
    low, high = np.minimum(a, b), np.maximum(a, b)
    key = low * np.int64(vertices) + high
    forward = (a < b).astype(np.int64)
    order = np.argsort(key, kind="stable")
    key, forward = key[order], forward[order]
    starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
    uses = np.diff(np.r_[starts, len(key)])
    forwards = np.add.reduceat(forward, starts)
    return {
        "edges": int(len(starts)),
        "boundary": int(np.count_nonzero(uses == 1)),
        "overshared": int(np.count_nonzero(uses > 2)),
        "misoriented": int(np.count_nonzero((uses == 2) & (forwards != 1))),
        "degenerate": degenerate,
        "bad_index": bad_index,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh")
    parser.add_argument("--json", action="store_true", help="one JSON line instead of text")
    args = parser.parse_args()
    vertices, triangles = read_triangles(args.mesh)
    counts = edge_counts(vertices, triangles)
    counts["nonmanifold"] = counts["boundary"] + counts["overshared"] + counts["misoriented"]
    result = {"vertices": vertices, "triangles": int(len(triangles)), **counts}
    if args.json:
        print(json.dumps(result))
    else:
        for key, value in result.items():
            print(f"{key:12} {value}")


if __name__ == "__main__":
    main()
