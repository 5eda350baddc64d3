"""Runs tracer: the resolved scene as JSON (the executable), and renders to float images (in process
with the tracer package built beside the executable when it is there, else the executable)."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from typing import TYPE_CHECKING

from tracer_tools import ROOT, package

from . import ToolError

if TYPE_CHECKING:
    import numpy as np

# tracer's options that the package's Scene.render takes as settings, by their keyword (the
# option's text is passed as it is: the package reads it as the command line does).
RENDER_SETTINGS = {
    "--width": "width",
    "--height": "height",
    "--samples": "samples",
    "--adaptive": "adaptive",
    "--max-depth": "max_depth",
    "--accel": "accel",
    "--leaf-size": "leaf_size",
}


class SceneError(ToolError):
    """tracer rejected the scene (its diagnostics went to stderr)."""

    exit_code = 3


def executable() -> pathlib.Path:
    """The tracer binary: $TRACER_BIN, else build/release/tracer of this checkout."""
    path = pathlib.Path(os.environ.get("TRACER_BIN", ROOT / "build" / "release" / "tracer"))
    if not path.is_file():
        raise ToolError(f"no tracer executable at {path}: run tools/bootstrap (or set TRACER_BIN)")
    return path


def overrides(
    width: int | None = None, height: int | None = None, samples: int | None = None, accel: str | None = None
) -> list[str]:
    """tracer's command-line overrides of the render block, for the values given."""
    args = []
    for flag, value in (("--width", width), ("--height", height), ("--samples", samples), ("--accel", accel)):
        if value is not None:
            args += [flag, str(value)]
    return args


def dump_json(scene_path: str | pathlib.Path, extra_args: Sequence[str] = ()) -> dict:
    """The scene description as tracer resolves it (`tracer --dump-json`), as a dict. Scene
    errors are printed by tracer itself, then raised as SceneError."""
    result = subprocess.run(
        [executable(), str(scene_path), "--dump-json", *extra_args], stdout=subprocess.PIPE, text=True
    )
    if result.returncode != 0:
        raise SceneError(f"tracer could not load {scene_path} (exit code {result.returncode})")
    return json.loads(result.stdout)


def render(scene_path: str | pathlib.Path, output: str | pathlib.Path, extra_args: Sequence[str] = ()) -> dict:
    """Renders with tracer to `output` (.exr keeps floats); returns tracer's statistics
    (--stats-json: render_seconds without process start-up, build times, ray counts)."""
    stats_path = pathlib.Path(output).with_suffix(".stats.json")
    result = subprocess.run(
        [executable(), str(scene_path), "-o", str(output), "--quiet", "--stats-json", str(stats_path), *extra_args]
    )
    if result.returncode != 0:
        raise SceneError(f"tracer could not render {scene_path} (exit code {result.returncode})")
    stats = json.loads(stats_path.read_text())
    stats_path.unlink()
    return stats


def package_call(extra_args: Sequence[str]) -> tuple[dict, dict, int] | None:
    """tracer's options `extra_args` as the package's (render settings, defines, threads); None
    when one of them has no equivalent there (the executable renders then)."""
    settings, defines, threads = {}, {}, 0
    args = list(extra_args)
    while args:
        flag, value = args.pop(0), args.pop(0) if args else None
        if value is None:
            return None
        if flag in RENDER_SETTINGS:
            settings[RENDER_SETTINGS[flag]] = value
        elif flag in ("-D", "--define") and "=" in value:
            name, text = value.split("=", 1)
            defines[name] = text
        elif flag == "--threads" and value.isdigit():
            threads = int(value)
        else:
            return None
    return settings, defines, threads


def render_pixels(scene_path: str | pathlib.Path, extra_args: Sequence[str] = ()) -> tuple[np.ndarray, dict]:
    """tracer's image of the scene as linear float32 (height, width, 3) and its statistics (as
    render's): in process with the tracer package beside executable() when it is built and takes
    every option (no process, no file), else by the executable through an EXR."""
    tracer = package.imported_beside(executable())
    call = package_call(extra_args)
    if tracer is not None and call is not None:
        settings, defines, threads = call
        try:
            scene = tracer.load(scene_path, defines=defines)
            return scene.render(**settings, threads=threads, return_stats=True)
        except tracer.SceneError as error:
            print(error, file=sys.stderr)
            raise SceneError(f"tracer could not load {scene_path}") from None
        except ValueError as error:
            raise SceneError(f"tracer could not render {scene_path}: {error}") from None
    from . import images

    with tempfile.TemporaryDirectory(prefix="tracer-render-") as folder:
        exr = pathlib.Path(folder) / "tracer.exr"
        stats = render(scene_path, exr, extra_args)
        return images.read_exr(exr), stats
