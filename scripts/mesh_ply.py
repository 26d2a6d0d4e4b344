"""Reads the binary PLY files `clmarch mesh` writes, for the mesh scripts (numpy only)."""
import numpy as np

TYPES = {"float": "<f4", "double": "<f8", "uchar": "u1", "uint": "<u4", "int": "<i4"}


def read_ply(path):
    """The vertex records (a structured array: x, y, z and what else the file has) and the faces
    (an F x 3 array of vertex numbers) of a binary little-endian PLY of triangles."""
    with open(path, "rb") as f:
        elements = []
        while (line := f.readline().decode().split())[0] != "end_header":
            if line[0] == "element":
                elements.append((line[1], int(line[2]), []))
            elif line[0] == "property" and line[1] != "list":
                elements[-1][2].append((line[2], TYPES[line[1]]))
        vertex = np.fromfile(f, dtype=np.dtype(elements[0][2]), count=elements[0][1])
        faces = np.fromfile(f, dtype=np.dtype([("n", "u1"), ("i", "<u4", 3)]), count=elements[1][1])
    return vertex, faces["i"]
