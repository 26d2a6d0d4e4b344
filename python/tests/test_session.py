"""A session keeps its program: a sweep of numbers builds at most twice per shape; Ctrl-C stops a
render with KeyboardInterrupt and leaves the session usable."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import clmarch
from conftest import SCENES, SMALL


def test_a_100_frame_sweep_builds_at_most_twice():
    session = clmarch.Session()
    scene = clmarch.load(SCENES / "torus.yaml", size=(32, 18))
    depths = []
    for k in range(100):
        frame = session.render(scene, set={"sdf.torus.minor_radius": 0.2 + 0.002 * k, "camera.fov": 40 + 0.1 * k})
        depths.append(frame["depth"].copy())
    assert session.programs_built <= 2
    assert frame.stats["literals"] == "buffer", "the edited scene reads its numbers from the values buffer"
    assert not np.array_equal(depths[0], depths[-1]), "the frames differ"
    # The last frame on its own (a fresh program, spelled) has the same picture.
    alone = clmarch.Session().render(scene, set={"sdf.torus.minor_radius": 0.2 + 0.002 * 99, "camera.fov": 49.9})
    assert np.allclose(alone["depth"], depths[-1], rtol=1e-5, equal_nan=True)


def test_an_animation_over_time_shares_programs():
    session = clmarch.Session()
    scene = clmarch.load(SCENES / "moving_shapes.yaml", size=(32, 18))
    for k in range(1, 30):
        session.render(scene, time=k / 24)
    assert session.programs_built <= 2


def test_ctrl_c_raises_keyboard_interrupt_and_the_session_goes_on(torus):
    session = clmarch.Session()
    # About a minute of CPU reference work (64 samples a pixel): only an interrupt ends it soon.
    slow = clmarch.load(SCENES / "mandelbulb.yaml", size=(1000, 1000), samples=64)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        session.render(slow, backend="reference")
    elapsed = time.monotonic() - start
    timer.join()
    assert elapsed < 30, f"the render stopped {elapsed:.1f} s after the interrupt was sent"
    frame = session.render(torus)
    assert np.isfinite(frame["depth"]).any(), "the session renders again after the interrupt"
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler, "Python's handler is back"


def test_sessions_pick_their_device():
    device = clmarch.devices()[0]
    frame = clmarch.Session(device=device["index"], lanes=1).render(SCENES / "torus.yaml", size=SMALL)
    assert frame.stats["lanes"] == 1
    assert frame.stats["device"].startswith(device["name"])
