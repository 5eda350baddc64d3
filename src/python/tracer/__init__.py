"""tracer from Python: scenes in, NumPy images out.

    import tracer
    scene = tracer.load("scenes/task2.scn")          # or tracer.loads(text)
    pixels = scene.render(width=300)                 # float32, shape (200, 300, 3), linear RGB
    tracer.write_image("out.png", pixels)            # as `tracer scene -o out.png` writes it

A scene with errors raises SceneError, which carries every diagnostic as data and prints as the
command line does. Rendering releases the GIL (other threads run; two scenes may render at once)
and stops with KeyboardInterrupt on Ctrl-C, or RenderStopped when its `stop` function says so.
NumPy is imported only when a render returns. See docs/guide/python.md.
"""

from __future__ import annotations

import os

from . import _tracer

# Annotations only (type checkers take the name TYPE_CHECKING as true): `import tracer` imports
# neither typing nor NumPy (the first render does), nor json (the first load does): 50 ms of
# imports on a busy machine, more than all of tracer's own.
TYPE_CHECKING = False
if TYPE_CHECKING:
    from collections.abc import Callable

    import numpy
    from numpy.typing import ArrayLike

__all__ = [
    "Diagnostic",
    "Picture",
    "RenderStopped",
    "Scene",
    "SceneError",
    "load",
    "loads",
    "show",
    "version",
    "write_image",
]

version: str = _tracer.version


class Diagnostic:
    """One error, warning or note, where the command line would print it.

    line and column are 1-based (column counts bytes; line 0: the whole file); `text` is what
    a terminal shows for it (the source line and a caret); `notes` are Diagnostics too.
    """

    __slots__ = ("severity", "path", "line", "column", "length", "message", "text", "repeats", "notes")

    def __init__(self, data: dict) -> None:
        self.severity: str = data.get("severity", "error")
        self.path: str = data.get("path", "")
        self.line: int = data.get("line", 0)
        self.column: int = data.get("column", 0)
        self.length: int = data.get("length", 0)
        self.message: str = data.get("message", "")
        self.text: str = data.get("text", "")
        self.repeats: int = data.get("repeats", 0)
        self.notes: list[Diagnostic] = [Diagnostic(note) for note in data.get("notes", [])]

    def __repr__(self) -> str:
        return f"Diagnostic({self.severity} at {self.path}:{self.line}:{self.column}: {self.message!r})"

    def __str__(self) -> str:
        return self.text or f"{self.path}:{self.line}:{self.column}: {self.severity}: {self.message}"


class SceneError(Exception):
    """A scene that did not load: `diagnostics` holds every problem found (errors, warnings and
    their notes), `text` what the command line prints, `unreadable` whether the file itself could
    not be read."""

    def __init__(self, report: dict) -> None:
        self.diagnostics: list[Diagnostic] = [Diagnostic(d) for d in report.get("diagnostics", [])]
        self.text: str = report.get("text", "")
        self.unreadable: bool = bool(report.get("unreadable", False))
        self.files_read: list[str] = list(report.get("files_read", []))
        first = next((d for d in self.diagnostics if d.severity == "error"), None)
        super().__init__(self.text.rstrip("\n") or (first.message if first else "the scene did not load"))

    @property
    def errors(self) -> list[Diagnostic]:
        """The diagnostics that are errors."""
        return [d for d in self.diagnostics if d.severity == "error"]


class RenderStopped(Exception):
    """A render that its `stop` function stopped before the end (no image)."""


class Scene:
    """A loaded scene with its meshes and image files: render it as often as you like, with any
    settings, from any thread."""

    def __init__(self, handle: _tracer.Scene, report: dict) -> None:
        self._handle = handle
        self.name: str = report.get("scene", "")
        self.warnings: list[Diagnostic] = [Diagnostic(d) for d in report.get("diagnostics", [])]
        self.files_read: list[str] = list(report.get("files_read", []))
        self._description: dict | None = None

    @property
    def description(self) -> dict:
        """The resolved scene as plain data: what `tracer --dump-json` prints."""
        if self._description is None:
            self._description = _json(_tracer.describe(self._handle))
        return self._description

    def render(
        self,
        *,
        width: int | None = None,
        height: int | None = None,
        samples: int | None = None,
        adaptive: float | tuple | str | None = None,
        max_depth: int | None = None,
        accel: str | None = None,
        leaf_size: int | None = None,
        threads: int = 0,
        region: tuple[int, int, int, int] | None = None,
        stop: Callable[[], bool] | None = None,
        encoding: str | None = None,
        return_stats: bool = False,
    ) -> numpy.ndarray | tuple[numpy.ndarray, dict]:
        """Renders the scene into a float32 NumPy array of shape (height, width, 3), linear RGB,
        row 0 at the top (the array owns the renderer's pixels: nothing is copied).

        The settings override the scene's render block as the command line's options do (one of
        width and height alone keeps the aspect ratio; adaptive is THRESHOLD, (THRESHOLD, DEPTH)
        or (THRESHOLD, DEPTH, CELL)); threads 0 uses every core; region (x0, y0, width, height)
        renders that window of the frame alone. With `encoding` ("linear" or "srgb") the pixels
        are the uint8 bytes an 8-bit file of the command line holds (rounded from the renderer's
        doubles: rounding the float32 array instead is one level off in about one value in
        100,000), else linear float32. `stop`, if given, is called every 20 ms while the
        render runs (on the calling thread, holding the GIL): when it returns true the render stops
        and RenderStopped is raised (`stop=event.is_set` stops it from another thread; Ctrl-C
        raises KeyboardInterrupt as ever). The world (the meshes' BVHs) is built on the first
        render and kept for the next ones with the same accel and leaf_size. With return_stats,
        returns (pixels, statistics), the statistics as `tracer --stats-json` writes them. A bad
        setting raises ValueError.
        """
        given = dict(
            width=width,
            height=height,
            samples=samples,
            adaptive=adaptive,
            max_depth=max_depth,
            accel=accel,
            leaf_size=leaf_size,
        )
        overrides = [(key, _setting_text(value)) for key, value in given.items() if value is not None]
        if isinstance(threads, bool) or not isinstance(threads, int):
            raise TypeError("threads must be a whole number (0: every core)")
        area = [] if region is None else [_whole(v, "region") for v in region]
        if region is not None and len(area) != 4:
            raise ValueError("region must be (x0, y0, width, height)")
        if stop is not None and not callable(stop):
            raise TypeError("stop must be a function of no arguments (e.g. a threading.Event's is_set)")
        rendered = _tracer.render(self._handle, overrides, threads, area, stop, encoding)
        if rendered is None:
            raise RenderStopped("the render was stopped by its stop function")
        pixels, stats = rendered
        return (pixels, _json(stats)) if return_stats else pixels

    def _repr_png_(self) -> bytes:
        """A notebook's view of the scene: a preview at most 400 pixels wide, sRGB."""
        width = self.description.get("render", {}).get("width", 400)
        pixels = self.render(width=min(int(width), 400))
        return _tracer.png_bytes(pixels, "srgb")

    def __repr__(self) -> str:
        return f"tracer.Scene({self.name!r})"


def _json(text: str) -> object:
    """`text` read as JSON (json imported on first use)."""
    import json

    return json.loads(text)


def _whole(value: object, what: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{what} must hold whole numbers, not {type(value).__name__}")
    return value


def _setting_text(value: object) -> str:
    """A render setting as the command line's text (adaptive's tuple joined by colons)."""
    if isinstance(value, tuple | list):
        return ":".join(_setting_text(part) for part in value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float | str):
        return repr(value) if isinstance(value, float) else str(value)
    raise TypeError(f"a render setting must be a number or a name, not {type(value).__name__}")


def _define_text(value: object) -> str:
    """A parameter's value as -D's text: numbers, booleans, vectors (3 numbers) and scene text."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(float(value)) if isinstance(value, float) else str(value)
    if isinstance(value, tuple | list):
        return "(" + ", ".join(_define_text(part) for part in value) + ")"
    if isinstance(value, str):
        return value
    raise TypeError(f"a parameter must be a number, a boolean, a vector or scene text, not {type(value).__name__}")


def _arguments(defines: dict | None, include: list | tuple) -> tuple[list, list]:
    pairs = [(str(name), _define_text(value)) for name, value in (defines or {}).items()]
    folders = [os.fspath(folder) for folder in include]
    # As the command line: -I's folders first, then TRACER_PATH's.
    folders += [folder for folder in os.environ.get("TRACER_PATH", "").split(":") if folder]
    return pairs, folders


def _loaded(path: str, text: str | None, defines: dict | None, include: list | tuple) -> Scene:
    pairs, folders = _arguments(defines, include)
    handle, report_text = _tracer.load(path, text, pairs, folders)
    report = _json(report_text)
    if handle is None:
        raise SceneError(report)
    return Scene(handle, report)


def load(path: str | os.PathLike, *, defines: dict | None = None, include: list | tuple = ()) -> Scene:
    """Loads the scene file at `path` with its meshes and images. `defines` sets the scene's
    parameters (declared by `param NAME = value`; as -D NAME=VALUE), `include` the folders
    `include` looks in (as -I). Raises SceneError if the scene has errors."""
    return _loaded(os.fspath(path), None, defines, include)


def loads(text: str, *, name: str = "<string>", defines: dict | None = None, include: list | tuple = ()) -> Scene:
    """Loads a scene from its text; `name` names it in messages and its folder is where relative
    paths (meshes, includes) start. Otherwise as load()."""
    if not isinstance(text, str):
        raise TypeError(f"text must be a str, not {type(text).__name__}")
    return _loaded(os.fspath(name), text, defines, include)


def write_image(path: str | os.PathLike, pixels: ArrayLike, *, encoding: str = "linear") -> None:
    """Writes float pixels of shape (height, width, 3) to `path` as the command line writes its
    images: the format by the extension (PNG, PPM, EXR, ...), 8-bit formats by `encoding`
    ("linear": round(255 v); "srgb": the sRGB curve, a PNG marked sRGB), written atomically.
    Raises OSError if it cannot be written."""
    _tracer.write_image(os.fspath(path), _float_pixels(pixels), encoding)


def _float_pixels(pixels: ArrayLike) -> numpy.ndarray:
    """`pixels` as a C-contiguous float32 array (a copy only if it is not one already)."""
    import numpy

    return numpy.ascontiguousarray(pixels, dtype=numpy.float32)


class Picture:
    """An image a notebook shows inline (8-bit PNG, by `encoding`)."""

    def __init__(self, pixels: ArrayLike, encoding: str = "srgb") -> None:
        self.pixels = _float_pixels(pixels)
        self.encoding = encoding

    def _repr_png_(self) -> bytes:
        return _tracer.png_bytes(self.pixels, self.encoding)


def show(pixels: ArrayLike, encoding: str = "srgb") -> Picture:
    """`pixels` as a Picture: the last line of a notebook cell shows it."""
    return Picture(pixels, encoding)
