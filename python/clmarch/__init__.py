"""clmarch: render, evaluate and check signed distance field scenes into NumPy.

    import clmarch
    scene = clmarch.load("scenes/torus.yaml")
    frame = clmarch.render(scene, size=(320, 180))
    depth = frame["depth"]          # float32, H x W, +inf where the ray missed
    frame.stats["kernel_ms"]

Every array is float32 and views the render's own memory (no copy); it keeps the render alive.
Bad input raises ValueError with the command line's one-line message ("file:line:col: ..."),
device failures RuntimeError, and Ctrl-C during a call KeyboardInterrupt (the session stays
usable). See docs/python.md.
"""

from __future__ import annotations

import atexit
import json
import logging
import os
import warnings
from typing import Any, Iterator, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _clmarch

__version__: str = _clmarch.__version__

__all__ = [
    "Scene", "Frame", "Session", "load", "render", "field", "mesh", "check", "bench", "devices",
    "programs_compiled", "set_verbosity", "set_progress", "__version__",
]

_log = logging.getLogger("clmarch")

Scene = _clmarch.Scene
"""A loaded, validated scene (see load). Properties: source_name, path, width, height, samples,
time, overrides."""

SceneSource = Union[str, "os.PathLike[str]", Mapping[str, Any]]
Overrides = Union[None, Mapping[str, Any], Sequence[str]]
Size = Optional[Tuple[int, int]]


def _emit_log() -> None:
    """Hands the library's lines of the last call to logging ("clmarch") and warnings."""
    for level, line in _clmarch.drain_log():
        if level == "warning":
            warnings.warn(line, RuntimeWarning, stacklevel=3)
        elif level == "verbose":
            _log.debug(line)
        else:
            _log.info(line)


def _call(function, *args, **kwargs):
    try:
        return function(*args, **kwargs)
    finally:
        _emit_log()


def _overrides(overrides: Overrides) -> list:
    """[(key path, YAML value)] from {"sdf.sphere.radius": 2} or ["sdf.sphere.radius=2"]."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        pairs = []
        for key, value in overrides.items():
            if not isinstance(key, str):
                raise ValueError(f"set: keys must be strings like 'render.epsilon' (got {key!r})")
            # YAML reads JSON: numbers, lists and mappings keep their types.
            pairs.append((key, value if isinstance(value, str) else json.dumps(value)))
        return pairs
    if isinstance(overrides, str):
        raise ValueError("set: expected a mapping or a list of 'key=value' strings (got one string)")
    return [_clmarch.parse_override(item) if isinstance(item, str) else _bad_override(item) for item in overrides]


def _bad_override(item):
    raise ValueError(f"set: expected 'key=value' strings (got {item!r})")


def _size(size: Size) -> Optional[Tuple[int, int]]:
    if size is None:
        return None
    if (not isinstance(size, (tuple, list)) or len(size) != 2
            or not all(isinstance(v, (int, np.integer)) and not isinstance(v, bool) for v in size)):
        raise ValueError(f"size must be (width, height) in pixels (got {size!r})")
    return int(size[0]), int(size[1])


def _time(time: Optional[float]) -> Optional[float]:
    if time is None:
        return None
    value = float(time)
    if not np.isfinite(value):
        raise ValueError(f"time must be a finite number of seconds (got {time!r})")
    return value


def load(source: SceneSource, *, set: Overrides = None, time: float = 0.0, size: Size = None,
         samples: Optional[int] = None) -> Scene:
    """Loads and validates a scene.

    source: a path (str or os.PathLike) of a YAML or JSON scene file; a mapping (the scene as a
    dict, as the file would hold it); or YAML text (a str holding a newline or starting with '{').
    set: overrides like the CLI's --set, {"sdf.sphere.radius": 2} or ["sdf.sphere.radius=2"].
    time: the time t of the scene's expressions, in seconds. size: (width, height), overriding
    render.width and render.height. samples: render.samples.
    """
    overrides, t, wh = _overrides(set), _time(time), _size(size)
    if isinstance(source, Mapping):
        return _call(_clmarch.load_scene, None, json.dumps(source), "<dict>", overrides, t, wh, samples)
    if isinstance(source, os.PathLike):
        return _call(_clmarch.load_scene, os.fspath(source), None, "", overrides, t, wh, samples)
    if not isinstance(source, str):
        raise ValueError(f"load: expected a path, a mapping or YAML text (got {type(source).__name__})")
    if "\n" in source or source.lstrip().startswith("{"):
        return _call(_clmarch.load_scene, None, source, "<text>", overrides, t, wh, samples)
    return _call(_clmarch.load_scene, source, None, "", overrides, t, wh, samples)


def _scene(scene: Union[Scene, SceneSource], set: Overrides, time: Optional[float], size: Size,
           samples: Optional[int]) -> Scene:
    """scene as given, or loaded again with the call's overrides, time, size and samples."""
    if not isinstance(scene, Scene):
        return load(scene, set=set, time=0.0 if time is None else time, size=size, samples=samples)
    if set is None and time is None and size is None and samples is None:
        return scene
    return _call(scene.changed, _overrides(set), _time(time), _size(size), samples)


class Frame(Mapping[str, np.ndarray]):
    """One render's arrays by channel name, and its figures.

    Channels (float32): "depth", "steps", "id", "status", "A", "samples", "R", "G", "B", "N.x",
    "N.y", "N.z", the shading's layers "ao.R" ... "specular.B", "P.x", "P.y", "P.z" (H x W), and
    "color", "normal", "P" (H x W x 3); "depth.lo" for double renders. They are the channels of
    `clmarch render --buffers` with the same names and values. stats: the figures of
    `clmarch render --stats`, with programs_built (programs the session compiled for this frame).
    """

    def __init__(self, channels: dict, stats: dict):
        self._channels = channels
        self.stats: dict = stats

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._channels[name]
        except KeyError:
            raise KeyError(f"no channel {name!r}; the channels are {', '.join(self._channels)}") from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._channels)

    def __len__(self) -> int:
        return len(self._channels)

    def __repr__(self) -> str:
        h, w = self._channels["depth"].shape
        return f"<clmarch.Frame {w}x{h}, {len(self)} channels, kernel {self.stats.get('kernel_ms', 0):.1f} ms>"


def _backend(backend: str) -> str:
    if backend not in ("opencl", "reference"):
        raise ValueError(f"backend must be 'opencl' or 'reference' (got {backend!r})")
    return backend


class Session:
    """Renders on one device and keeps its program between calls: a sweep or an animation of one
    scene builds at most two programs (the first scene's, spelled; then one that reads every number
    from a buffer). device: the index of clmarch.devices() (default: first GPU, else first CPU);
    lanes: pixels per work-item, 1, 4, 8 or 16 (default: the device's)."""

    def __init__(self, device: Optional[int] = None, lanes: Optional[int] = None):
        self._session = _call(_clmarch.Session, device, lanes)
        self.device = device
        self.lanes = lanes

    def render(self, scene: Union[Scene, SceneSource], *, size: Size = None, set: Overrides = None,
               time: Optional[float] = None, samples: Optional[int] = None, backend: str = "opencl") -> Frame:
        """Renders scene (a Scene, or what load takes) with the call's overrides; see clmarch.render."""
        chosen = _scene(scene, set, time, size, samples)
        channels, stats = _call(self._session.render, chosen, _backend(backend), True)
        return Frame(channels, json.loads(stats))

    @property
    def programs_built(self) -> int:
        """Programs this session compiled (programs found in the process's store not counted)."""
        return self._session.programs_built

    @property
    def source(self) -> str:
        """The OpenCL C of the current program (`render --dump-kernel`'s text)."""
        return self._session.source


_default_session: Optional[Session] = None


def _session() -> Session:
    global _default_session
    if _default_session is None:
        _default_session = Session()
    return _default_session


def render(scene: Union[Scene, SceneSource], *, size: Size = None, set: Overrides = None,
           time: Optional[float] = None, samples: Optional[int] = None, backend: str = "opencl",
           session: Optional[Session] = None) -> Frame:
    """Renders scene and returns its Frame of arrays.

    size: (width, height); set: overrides as in load; time: t in seconds; samples: rays per pixel;
    backend: "opencl" (the device) or "reference" (the double-precision CPU renderer). The module's
    default Session keeps programs between calls; pass session= for another device.
    """
    return (session or _session()).render(scene, size=size, set=set, time=time, samples=samples, backend=backend)


def field(scene: Union[Scene, SceneSource], points: np.ndarray, *, backend: str = "opencl",
          device: Optional[int] = None, lanes: Optional[int] = None) -> dict:
    """The scene's field at points (an N x 3 array, world coordinates): {"distance": (N,),
    "color": (N, 3), "id": (N,)}, float32. Tiled scenes repeat their cell. OpenCL evaluates the
    generated distance function in the scene's render.precision; the reference in double; either is
    rounded to float32 here (`clmarch field` writes a double's digits)."""
    chosen = _scene(scene, None, None, None, None)
    array = np.asarray(points, dtype=np.float64)
    distance, color, ids = _call(_clmarch.field, chosen, array, _backend(backend), device, lanes)
    return {"distance": distance, "color": color, "id": ids}


def mesh(scene: Union[Scene, SceneSource], *, resolution: int = 256, set: Overrides = None,
         time: Optional[float] = None, backend: str = "opencl", precision: str = "float",
         device: Optional[int] = None, cells: str = "cubes", sharp: bool = False) -> dict:
    """`clmarch mesh`: the scene's surface as a welded, watertight triangle mesh.

    Returns {"vertices": (V, 3) float64, "faces": (F, 3) uint32 (counter-clockwise seen from
    outside), "normals": (V, 3) float32, "colors": (V, 3) float32 (linear), "stats": dict}.
    resolution: grid cells along the longest side of the surface's box; precision "double"
    evaluates the field in double (for scenes far from the origin); cells "cubes" (marching cubes)
    or "tetrahedra" (about three times the triangles); sharp keeps edges and corners (`--sharp`,
    cubes only).
    """
    chosen = _scene(scene, set, time, None, None)
    vertices, faces, normals, colors, stats = _call(_clmarch.mesh, chosen, int(resolution), _backend(backend),
                                                    precision, device, cells, bool(sharp))
    return {"vertices": vertices, "faces": faces, "normals": normals, "colors": colors, "stats": json.loads(stats)}


def check(scene: Union[Scene, SceneSource], *, size: Size = None, set: Overrides = None,
          time: Optional[float] = None, samples: Optional[int] = None, device: Optional[int] = None,
          lanes: Optional[int] = None) -> dict:
    """`clmarch check --json`: the scene on OpenCL against the CPU reference; report["passed"]."""
    chosen = _scene(scene, set, time, size, samples)
    return json.loads(_call(_clmarch.check, chosen, device, lanes))


def bench(scene: Union[Scene, SceneSource], *, size: Size = None, set: Overrides = None,
          time: Optional[float] = None, repeat: int = 5, reference: bool = True, device: Optional[int] = None,
          lanes: Optional[int] = None) -> dict:
    """`clmarch bench --json`: median kernel times, rays/s and steps against the device's ceiling."""
    chosen = _scene(scene, set, time, size, None)
    return json.loads(_call(_clmarch.bench, chosen, int(repeat), bool(reference), device, lanes))


def devices() -> list:
    """The OpenCL devices, as `clmarch devices` numbers them: index, name, platform, type, fp64."""
    return _call(_clmarch.devices)


def programs_compiled() -> int:
    """OpenCL programs compiled by this process so far (all sessions)."""
    return _clmarch.programs_compiled()


def set_verbosity(level: str) -> None:
    """"quiet", "normal" (default) or "verbose": which lines go to the logger "clmarch"."""
    _clmarch.set_verbosity(level)


def set_progress(callback) -> None:
    """callback(label, done, total) receives the progress of long work (the reference's rows, a
    render's chunks, a mesh's bricks, the frames of a sweep) at most four times a second and once
    at its end, instead of the line the CLI draws; None stops it. An exception in the callback is
    reported as unraisable and stops the work as Ctrl-C does (the call raises KeyboardInterrupt)."""
    _clmarch.set_progress(callback)


atexit.register(_clmarch.set_progress, None)
