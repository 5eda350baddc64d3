"""Shared set-up of the cross-check tests: the tracer executable."""

import json
import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
HERE = pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="session")
def tracer_bin():
    from tracer_tools.xcheck import ToolError, tracer_cli

    try:
        path = tracer_cli.executable()  # $TRACER_BIN, else build/release/tracer
    except ToolError as error:
        pytest.fail(str(error))
    os.environ["TRACER_BIN"] = str(path)
    return path


@pytest.fixture(scope="session")
def dump(tracer_bin):
    """dump(scene, *extra_args) -> the scene description dict from `tracer --dump-json`."""

    def run(scene, *extra):
        return json.loads(subprocess.check_output([tracer_bin, str(scene), "--dump-json", *extra]))

    return run


def run_tool(module, *args, env=None):
    """Runs `python -m xcheck.<module> args` as the launcher does; returns CompletedProcess."""
    paths = [env["PYTHONPATH"]] if env and "PYTHONPATH" in env else []
    environment = {**os.environ, **(env or {}), "PYTHONPATH": os.pathsep.join(paths + [str(ROOT / "tools")])}
    return subprocess.run(
        [sys.executable, "-m", f"tracer_tools.xcheck.{module}", *map(str, args)],
        capture_output=True,
        text=True,
        env=environment,
        cwd=ROOT,
    )
