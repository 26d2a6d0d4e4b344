"""Shared fixtures of the Python module's tests: the scenes folder, the CLI to compare with, and
one small torus scene whose program the tests share (each new program costs a PoCL compile)."""

import os
import pathlib
import subprocess

import pytest

import clmarch

SCENES = pathlib.Path(os.environ.get("CLMARCH_SCENES", pathlib.Path(__file__).parents[2] / "scenes"))
CLI = os.environ.get("CLMARCH_EXECUTABLE", str(pathlib.Path(__file__).parents[2] / "build" / "clmarch"))

# A size every packet width divides, small enough that a reference render takes milliseconds.
SMALL = (64, 36)


@pytest.fixture(scope="session")
def torus():
    return clmarch.load(SCENES / "torus.yaml", size=SMALL)


def run_cli(*args):
    """Runs the clmarch executable; returns the completed process (raises on a non-zero exit)."""
    return subprocess.run([CLI, *map(str, args)], check=True, capture_output=True, text=True)
