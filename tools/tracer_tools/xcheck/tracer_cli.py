"""Runs the tracer executable: the resolved scene as JSON, and renders to float images."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
from collections.abc import Sequence

from tracer_tools import ROOT

from . import ToolError


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
