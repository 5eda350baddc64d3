"""Shared set-up of the region and farm tests: the tracer executable, images read as arrays."""

import os
import pathlib
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio
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


def read_pixels(path):
    """An image file's pixels (height x width x 3) in its own type, and its spec."""
    image = oiio.ImageInput.open(str(path))
    assert image is not None, f"cannot read {path}: {oiio.geterror()}"
    spec = image.spec()
    pixels = image.read_image(spec.format)
    image.close()
    return np.asarray(pixels).reshape(spec.height, spec.width, spec.nchannels), spec


def render(tracer, scene, output, *arguments):
    """tracer SCENE -o OUTPUT ARGUMENTS, which must succeed; the image's pixels."""
    subprocess.run([str(tracer), str(scene), "-o", str(output), "-q", *map(str, arguments)], check=True)
    return read_pixels(output)[0]


def farm(*arguments, tracer=None, env=None, **popen):
    """tools/farm ARGUMENTS (run with this Python, as the launcher does); the CompletedProcess."""
    command = [sys.executable, "-m", "tracer_tools.farm.farm", *map(str, arguments)]
    if tracer:
        command += ["--tracer", str(tracer)]
    environment = {**os.environ, **(env or {}), "PYTHONPATH": str(ROOT / "tools")}
    return subprocess.run(command, capture_output=True, text=True, env=environment, **{"cwd": ROOT, **popen})
