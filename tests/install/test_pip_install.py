"""The README's install of the Python package, as a user runs it (docs/guide/python.md): a fresh
clone of this checkout's commit, a new virtual environment from the system's python3, and
`pip install .` (scikit-build-core and nanobind fetched by pip, tracer's C++ core built by CMake);
then the installed package renders task2 as the command line does. Run by ctest
(`python_install`): it builds the core once more, a few minutes on 2 cores."""

import os
import pathlib
import shutil
import subprocess

import numpy
import OpenImageIO as oiio
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TRACER = os.environ.get("TRACER_BIN", str(ROOT / "build" / "release" / "tracer"))
RENDER = """
import sys, numpy, tracer
pixels = tracer.load(sys.argv[1]).render(width=120, threads=1)
numpy.save(sys.argv[2], pixels)
print(tracer.__file__)
"""


def run(command, cwd=None):
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    assert (
        result.returncode == 0
    ), f"{' '.join(map(str, command))} failed:\n{result.stdout[-4000:]}{result.stderr[-4000:]}"
    return result.stdout


def test_pip_install_from_a_fresh_clone_renders_as_the_command_line(tmp_path):
    if not (ROOT / ".git").exists() or shutil.which("git") is None:
        pytest.skip("not a git checkout: nothing to clone")
    clone, venv = tmp_path / "clone", tmp_path / "venv"
    run(["git", "clone", "--quiet", str(ROOT), str(clone)])
    run(["python3", "-m", "venv", str(venv)])
    run([venv / "bin" / "pip", "install", "--quiet", "--disable-pip-version-check", "."], cwd=clone)
    where = run(
        [venv / "bin" / "python", "-c", RENDER, ROOT / "scenes" / "task2.scn", tmp_path / "px.npy"], cwd=tmp_path
    )
    assert str(venv) in where  # the installed package, not the checkout's build
    ours = numpy.load(tmp_path / "px.npy")
    out = tmp_path / "cli.exr"
    subprocess.run([TRACER, ROOT / "scenes" / "task2.scn", "-o", out, "-q", "--width", "120"], check=True)
    image = oiio.ImageInput.open(str(out))
    theirs = image.read_image(format=oiio.FLOAT)
    image.close()
    assert ours.shape == theirs.shape == (80, 120, 3)
    # The same source with the same flags: equal up to the compilers' own choices (IPO, inlining).
    assert numpy.abs(ours - theirs).max() <= 1e-5
