"""The module's surface: its type stubs name exactly what the extension defines; check, bench and
devices return the CLI's --json figures; loading takes paths, text and dicts alike."""

import ast
import inspect
import pathlib

import numpy as np
import pytest

import clmarch
from clmarch import _clmarch
from conftest import SCENES, SMALL, run_cli


def stub_names():
    tree = ast.parse((pathlib.Path(clmarch.__file__).parent / "_clmarch.pyi").read_text())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    return names


def test_the_stubs_name_what_the_extension_defines():
    defined = {name for name in dir(_clmarch) if not name.startswith("_")} | {"__version__"}
    assert stub_names() == defined


def test_every_public_call_is_documented():
    for name in clmarch.__all__:
        item = getattr(clmarch, name)
        if callable(item):
            assert inspect.getdoc(item), name


def test_paths_text_and_dicts_load_the_same_scene():
    path = SCENES / "two_spheres.yaml"
    text = path.read_text()
    from_path = clmarch.render(clmarch.load(str(path), size=SMALL))
    from_text = clmarch.render(clmarch.load(text, size=SMALL))
    assert np.array_equal(from_path["depth"], from_text["depth"])
    epsilon = 1e-4
    scene = clmarch.load({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0]},
                          "render": {"epsilon": epsilon}, "sdf": {"sphere": {"radius": 1}}}, size=SMALL)
    frame = clmarch.render(scene)
    hits = np.isfinite(frame["depth"])
    assert hits.sum() > 100
    # A hit stops within epsilon of the unit sphere; P adds float rounding of a point 3 units away.
    radius = np.linalg.norm(frame["P"][hits].astype(np.float64), axis=1)
    assert np.all(np.abs(radius - 1.0) <= epsilon + 8 * np.finfo(np.float32).eps * 4)


def test_overrides_and_time_reload_the_scene(torus):
    wider = torus.changed([("camera.fov", "70")], None, None, None)
    assert wider.overrides == [("camera.fov", "70")] and torus.overrides == []
    assert (torus.width, torus.height) == SMALL
    moved = clmarch.load(SCENES / "moving_shapes.yaml", time=1.5)
    assert moved.time == 1.5


def test_check_passes_on_the_torus(torus):
    report = clmarch.check(torus)
    assert report["passed"] is True
    assert report["pixels"] == SMALL[0] * SMALL[1]


def test_bench_and_devices_give_the_clis_figures(torus):
    report = clmarch.bench(torus, repeat=1, reference=False)
    assert report["kernel_ms"] > 0 and report["depth_kernel_ms"] > 0 and report["width"] == SMALL[0]
    devices = clmarch.devices()
    listed = run_cli("devices").stdout
    assert devices and all(d["name"] in listed for d in devices)


def test_logging_goes_to_the_clmarch_logger(torus, caplog):
    clmarch.set_verbosity("verbose")
    try:
        with caplog.at_level("DEBUG", logger="clmarch"):
            clmarch.Session(lanes=4).render(torus)
    finally:
        clmarch.set_verbosity("normal")
    assert any("build" in record.getMessage() for record in caplog.records)


def test_the_package_version_is_the_projects():
    import re
    import tomllib
    root = pathlib.Path(__file__).parents[2]
    cmake = re.search(r"project\(clmarch VERSION ([0-9.]+)", (root / "CMakeLists.txt").read_text()).group(1)
    pyproject = tomllib.loads((root / "pyproject.toml").read_text())["project"]["version"]
    assert clmarch.__version__ == cmake == pyproject
    assert run_cli("--version").stdout.strip() == f"clmarch {cmake}"


def test_progress_goes_to_a_callback():
    calls = []
    clmarch.set_progress(lambda label, done, total: calls.append((label, done, total)))
    try:
        clmarch.render(SCENES / "mandelbulb.yaml", size=(320, 320), backend="reference")
    finally:
        clmarch.set_progress(None)
    assert calls, "the reference's rows report progress"
    label, done, total = calls[-1]
    assert done == total and all(d <= t for _, d, t in calls)
    with pytest.raises(ValueError, match="expected a callable or None"):
        clmarch.set_progress(42)
