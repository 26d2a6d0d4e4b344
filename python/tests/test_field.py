"""clmarch.field: the scene's distances and colours at points, on both backends, against closed
forms."""

import numpy as np
import pytest

import clmarch
from conftest import SCENES

SPHERE = {"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
          "sdf": {"sphere": {"center": [0.5, 0, 0], "radius": 1.25, "color": [0.2, 0.4, 0.6]}}}


@pytest.mark.parametrize("backend", ["opencl", "reference"])
def test_a_sphere_field_is_its_closed_form(backend):
    points = np.random.default_rng(3).uniform(-4, 4, size=(1000, 3))
    samples = clmarch.field(SPHERE, points, backend=backend)
    offset = np.linalg.norm(points - [0.5, 0, 0], axis=1)
    expected = offset - 1.25
    # The reference's double distance rounded once to float: half an ulp of the distance. OpenCL
    # rounds the coordinates to float and takes a float length (about 6 roundings of |p - c|).
    eps = np.finfo(np.float32).eps
    tolerance = eps * np.abs(expected) if backend == "reference" else 8 * eps * np.max(offset)
    assert samples["distance"].shape == (1000,) and samples["distance"].dtype == np.float32
    assert np.all(np.abs(samples["distance"] - expected) <= tolerance)
    assert np.allclose(samples["color"], [0.2, 0.4, 0.6])
    assert samples["color"].shape == (1000, 3) and np.all(samples["id"] == 0)


def test_both_backends_agree_on_a_shipped_scene():
    scene = clmarch.load(SCENES / "operators_demo.yaml")
    points = np.random.default_rng(5).uniform(-3, 3, size=(500, 3))
    device = clmarch.field(scene, points)
    reference = clmarch.field(scene, points, backend="reference")
    # Float against double through the tree's few dozen operations: 32 ulps of the coordinates'
    # magnitude (the blends' k and the radii are of that size too).
    scale = max(1.0, np.max(np.abs(points)))
    assert np.max(np.abs(device["distance"] - reference["distance"])) <= 32 * np.finfo(np.float32).eps * scale
    assert np.array_equal(device["id"], reference["id"])


def test_no_points_give_empty_arrays():
    samples = clmarch.field(SPHERE, np.zeros((0, 3)))
    assert samples["distance"].shape == (0,) and samples["color"].shape == (0, 3)
