"""Shared set-up of the authoring-loop tests (watch, preview page, language server, grammar)."""

import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"


@pytest.fixture(scope="session")
def tracer_bin():
    from tracer_tools.xcheck import ToolError, tracer_cli

    try:
        path = tracer_cli.executable()  # $TRACER_BIN, else build/release/tracer
    except ToolError as error:
        pytest.fail(str(error))
    return path


def start_tool(name, *args, **popen):
    """tools/NAME ARGS in the background, as the launcher runs it (python -m tracer_tools NAME) but
    without its bootstrap step; `popen`: subprocess.Popen's keywords (pipes)."""
    environment = dict(os.environ, PYTHONPATH=str(ROOT / "tools"))
    return subprocess.Popen([sys.executable, "-m", "tracer_tools", name, *map(str, args)], env=environment, **popen)


def start_preview(tracer_bin, scene, output, port):
    """tools/preview SCENE -o OUTPUT --port PORT, its stdout and stderr piped as text."""
    return start_tool(
        "preview",
        scene,
        "-o",
        output,
        "--port",
        port,
        "--tracer",
        tracer_bin,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
