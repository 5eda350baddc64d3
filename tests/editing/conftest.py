"""Shared set-up of the authoring-loop tests (watch, preview page, language server, grammar)."""

import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"
sys.path.insert(0, str(ROOT / "tools"))


@pytest.fixture(scope="session")
def tracer_bin():
    path = pathlib.Path(os.environ.get("TRACER_BIN", ROOT / "build" / "release" / "tracer"))
    if not path.is_file():
        pytest.fail(f"no tracer executable at {path} (build it, or set TRACER_BIN)")
    return path
