"""Renders into arrays: the same channels, bit for bit, as `clmarch render --buffers`; views of the
render's memory, never copies; the GIL released while rendering."""

import threading
import time
import tracemalloc

import numpy as np
import OpenImageIO as oiio
import pytest

import clmarch
from conftest import SCENES, SMALL, run_cli

# The EXR's channels that are the module's under the same name.
EXR_CHANNELS = ["R", "G", "B", "depth", "steps", "N.x", "N.y", "N.z", "A", "samples", "id", "status",
                "ao.R", "ao.G", "ao.B", "diffuse.R", "diffuse.G", "diffuse.B", "specular.R", "specular.G",
                "specular.B", "P.x", "P.y", "P.z"]


def read_exr(path):
    image = oiio.ImageInput.open(str(path))
    assert image, oiio.geterror()
    spec = image.spec()
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    return {name: np.ascontiguousarray(pixels[:, :, k]) for k, name in enumerate(spec.channelnames)}


def same_bits(a, b):
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))


@pytest.mark.parametrize("backend", ["opencl", "reference"])
def test_channels_equal_the_cli_buffers_bit_for_bit(tmp_path, backend):
    scene = SCENES / "checker_floor.yaml"
    frame = clmarch.render(scene, size=SMALL, backend=backend, set={"shading.view": "shaded"})
    exr = tmp_path / "buffers.exr"
    run_cli("render", scene, "--size", f"{SMALL[0]}x{SMALL[1]}", "--backend", backend, "--set",
            "shading.view=shaded", "--buffers", exr, "--no-image", "--stats", "--quiet")
    channels = read_exr(exr)
    for name in EXR_CHANNELS:
        assert same_bits(frame[name], channels[name]), f"{backend}: channel {name} differs from the EXR's"
    assert same_bits(frame["depth"], channels["Z"])
    assert np.isinf(frame["depth"]).any() and np.isfinite(frame["depth"]).any(), "the scene has hits and misses"
    h, w = frame["depth"].shape
    assert (w, h) == SMALL
    for composite, parts in [("color", "RGB"), ("normal", ["N.x", "N.y", "N.z"]), ("P", ["P.x", "P.y", "P.z"])]:
        assert frame[composite].shape == (h, w, 3)
        for k, part in enumerate(parts):
            assert same_bits(np.ascontiguousarray(frame[composite][:, :, k]), frame[part])


def test_arrays_view_the_render_and_keep_it_alive(torus):
    frame = clmarch.render(torus, size=(256, 144))
    tracemalloc.start()
    try:
        arrays = {name: frame[name] for name in frame}
        again = {name: frame[name] for name in frame}
        allocated, _ = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    total = sum(a.nbytes for a in arrays.values())
    # 27 planes of 147 KB pass to Python, and NumPy allocates no data for them (its allocations
    # are traced): what remains is the arrays' headers.
    assert total > 27 * 256 * 144 * 4 - 1
    assert allocated < total / 50, f"{allocated} bytes allocated handing out {total} bytes of arrays"
    for name, array in arrays.items():
        assert array.dtype == np.float32 and not array.flags.owndata, name
        assert array.__array_interface__["data"][0] == again[name].__array_interface__["data"][0], name
    depth = arrays["depth"].copy()
    del frame, again
    assert same_bits(arrays["depth"], depth), "an array outlives its frame with its values"


def test_the_gil_is_released_while_rendering(torus):
    scene = clmarch.load(SCENES / "mandelbulb.yaml", size=(400, 400))
    ticks = []
    worker = threading.Thread(target=lambda: clmarch.render(scene, backend="reference"))
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    assert len(ticks) > 20, "the main thread ran while the other rendered"


def test_stats_are_the_cli_figures(torus):
    frame = clmarch.render(torus)
    for key in ["backend", "device", "lanes", "precision", "width", "height", "build_ms", "kernel_ms", "steps",
                "rays_per_s", "literals", "out_of_steps", "programs_built"]:
        assert key in frame.stats, key
    assert frame.stats["steps"] == int(frame["steps"].sum(dtype=np.float64))
    assert frame.stats["width"] == SMALL[0] and frame.stats["height"] == SMALL[1]
