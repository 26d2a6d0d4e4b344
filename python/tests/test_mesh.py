"""clmarch.mesh: the surface as arrays, watertight, on the surface, the same as the CLI's file."""

import collections

import numpy as np
import pytest

import clmarch
from conftest import SCENES, run_cli


def test_a_sphere_mesh_is_closed_and_on_the_sphere():
    scene = {"sdf": {"sphere": {"center": [0.25, 0, 0], "radius": 1, "color": [0.1, 0.7, 0.3]}}}
    result = clmarch.mesh(scene, resolution=24)
    vertices, faces = result["vertices"], result["faces"]
    assert vertices.dtype == np.float64 and faces.dtype == np.uint32 and result["normals"].shape == vertices.shape
    directed = collections.Counter(map(tuple, np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])))
    assert all(count == 1 and directed[(b, a)] == 1 for (a, b), count in directed.items()), "watertight"
    radius = np.linalg.norm(vertices - [0.25, 0, 0], axis=1)
    # The device's float field: within its float rounding of the coordinates (about 1.3) and the
    # root finding's tolerance (1e-4 of a cell) of 1.
    assert np.max(np.abs(radius - 1)) < 8 * np.finfo(np.float32).eps * 1.3 + 1e-4 * result["stats"]["cell"]
    assert np.allclose(result["colors"], [0.1, 0.7, 0.3], atol=1e-6)
    assert result["stats"]["triangles"] == len(faces)


def test_the_mesh_is_the_clis(tmp_path):
    out = tmp_path / "torus.stl"
    run_cli("mesh", SCENES / "torus.yaml", "-o", out, "--resolution", 32, "--quiet")
    result = clmarch.mesh(SCENES / "torus.yaml", resolution=32)
    # Binary STL: an 80-byte header, a triangle count, 50 bytes a triangle.
    data = out.read_bytes()
    count = int.from_bytes(data[80:84], "little")
    assert count == len(result["faces"]) and len(data) == 84 + 50 * count


def test_tetrahedra_give_more_triangles_than_cubes():
    cubes = clmarch.mesh(SCENES / "torus.yaml", resolution=24)
    tetrahedra = clmarch.mesh(SCENES / "torus.yaml", resolution=24, cells="tetrahedra")
    assert cubes["stats"]["cell_method"] == "cubes" and tetrahedra["stats"]["cell_method"] == "tetrahedra"
    assert 2.5 < len(tetrahedra["faces"]) / len(cubes["faces"]) < 3.5


def test_sharp_features_add_fans_on_a_box_and_keep_it_closed():
    box = {"sdf": {"box": {"half_size": [0.5, 0.3, 0.4], "rotate": [10, 20, 30]}}}
    plain = clmarch.mesh(box, resolution=24, backend="reference")
    sharp = clmarch.mesh(box, resolution=24, backend="reference", sharp=True)
    assert plain["stats"]["feature_cells"] == 0 and sharp["stats"]["feature_cells"] > 0
    assert sharp["stats"]["sharp"] and len(sharp["vertices"]) > len(plain["vertices"])
    edges = {}
    for a, b, c in sharp["faces"].tolist():
        for edge in ((a, b), (b, c), (c, a)):
            edges[edge] = edges.get(edge, 0) + 1
    assert all(count == 1 and edges.get((b, a)) == 1 for (a, b), count in edges.items())


def test_bad_mesh_arguments():
    with pytest.raises(ValueError, match="resolution must be from 8 to 8192"):
        clmarch.mesh(SCENES / "torus.yaml", resolution=4)
    with pytest.raises(ValueError, match="precision must be 'float' or 'double'"):
        clmarch.mesh(SCENES / "torus.yaml", precision="half")
    with pytest.raises(ValueError, match="cells must be 'cubes' or 'tetrahedra'"):
        clmarch.mesh(SCENES / "torus.yaml", resolution=16, cells="hexagons")
    with pytest.raises(ValueError, match="sharp applies to cells='cubes'"):
        clmarch.mesh(SCENES / "torus.yaml", resolution=16, cells="tetrahedra", sharp=True)
    with pytest.raises(ValueError, match="the surface is unbounded"):
        clmarch.mesh({"sdf": {"plane": {"normal": [0, 1, 0], "offset": 0}}}, resolution=8)
