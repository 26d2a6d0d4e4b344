"""Every bad call raises ValueError (input), naming the file, line:column or argument as the CLI
does, and leaves nothing half done."""

import os
import subprocess
import sys

import numpy as np
import pytest

import clmarch
from conftest import CLI, SCENES


def error_of(call):
    with pytest.raises(ValueError) as caught:
        call()
    return str(caught.value)


def test_a_missing_file_names_it():
    assert error_of(lambda: clmarch.load("/no/such/scene.yaml")).startswith("/no/such/scene.yaml")


def test_yaml_text_errors_give_line_and_column():
    message = error_of(lambda: clmarch.load("camera: {fov: 40}\nsdf:\n  sphere: {radius: -1}\n"))
    assert message.startswith("<text>:3:"), message
    assert "radius" in message


def test_a_dict_error_names_the_key():
    message = error_of(lambda: clmarch.load({"sdf": {"sphere": {"radius": 1, "colour": [1, 0, 0]}}}))
    assert message.startswith("<dict>:") and "colour" in message, message


def test_the_cli_and_python_give_the_same_message(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("sdf:\n  sphere: {radius: 0}\n")
    cli = subprocess.run([CLI, "render", str(bad), "--no-image", "--stats"], capture_output=True, text=True)
    assert cli.returncode == 2
    assert error_of(lambda: clmarch.load(bad)) in cli.stderr


@pytest.mark.parametrize("call, expected", [
    (lambda s: clmarch.render(s, backend="gpu"), "backend must be 'opencl' or 'reference'"),
    (lambda s: clmarch.render(s, size=(0, 10)), "width and height must be in [1, 65536]"),
    (lambda s: clmarch.render(s, size=(10,)), "size must be (width, height)"),
    (lambda s: clmarch.render(s, samples=0), "samples must be in [1, 1024]"),
    (lambda s: clmarch.render(s, time=float("nan")), "time must be a finite number"),
    (lambda s: clmarch.render(s, set={"sdf.torus.radius": 1}), "unknown key 'radius'"),
    (lambda s: clmarch.render(s, set=["render.epsilon"]), "render.epsilon"),
    (lambda s: clmarch.render(s, set="render.epsilon=1"), "a mapping or a list"),
    (lambda s: clmarch.Session(lanes=3).render(s), "lanes must be 1, 4, 8 or 16"),
    (lambda s: clmarch.Session(device=99).render(s), "99"),
    (lambda s: clmarch.field(s, np.zeros((4, 2))), "points must be an N x 3 array"),
    (lambda s: clmarch.field(s, [[0, 0, np.inf]]), "every coordinate must be finite"),
    (lambda s: clmarch.bench(s, repeat=0), "repeat must be from 1 to 1000"),
    (lambda s: clmarch.load(42), "expected a path, a mapping or YAML text"),
    (lambda s: clmarch.set_verbosity("loud"), "verbosity must be quiet, normal or verbose"),
])
def test_bad_arguments(torus, call, expected):
    message = error_of(lambda: call(torus))
    assert expected in message, message
    assert "\n" not in message


def test_an_unknown_channel_lists_the_channels(torus):
    frame = clmarch.render(torus)
    with pytest.raises(KeyError, match="the channels are"):
        frame["Z"]


def test_device_errors_are_runtime_errors(tmp_path):
    # Without an OpenCL platform (an ICD loader pointed at an empty folder) the OpenCL backend fails
    # with the CLI's "no OpenCL device" message; the reference still renders.
    program = (
        "import clmarch\n"
        f"scene = clmarch.load({str(SCENES / 'torus.yaml')!r}, size=(8, 8))\n"
        "assert clmarch.devices() == []\n"
        "clmarch.render(scene, backend='reference')\n"
        "try:\n"
        "    clmarch.render(scene)\n"
        "except RuntimeError as e:\n"
        "    print('RuntimeError:', e)\n")
    env = dict(os.environ, OCL_ICD_VENDORS=str(tmp_path), OPENCL_VENDOR_PATH=str(tmp_path))
    run = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith("RuntimeError:") and "OpenCL" in run.stdout, run.stdout
