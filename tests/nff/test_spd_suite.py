"""tools/spd end to end on one scene without Mitsuba and Embree (needs ../shared/spd: skipped
with a message on a clone without it)."""

import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPD = ROOT.parent / "shared" / "spd"


@pytest.mark.skipif(not (SPD / "src" / "tetra.c").is_file(), reason=f"no SPD sources at {SPD} (../shared absent)")
def test_the_suite_builds_generates_converts_renders_and_reports(tmp_path):
    environment = {**os.environ, "PYTHONPATH": str(ROOT / "tools")}
    command = [
        sys.executable,
        "-m",
        "tracer_tools.spd.suite",
        "--scenes",
        "tetra",
        "--no-crosscheck",
        "--no-embree",
        "--out",
        str(tmp_path / "out"),
        "--docs",
        str(tmp_path / "spd.md"),
        "--runs",
        "1",
    ]
    done = subprocess.run(command, capture_output=True, text=True, env=environment, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    # The generator's output is upstream's file, unchanged.
    assert (tmp_path / "out" / "tetra" / "tetra.nff").read_bytes() == (SPD / "nff" / "tetra.nff").read_bytes()
    (result,) = json.loads((tmp_path / "out" / "results.json").read_text())
    rays = result["stats"]["rays"]
    assert rays["primary"] == 513 * 513  # rays through the pixel corners
    assert 0 < rays["primary_hits"] < rays["primary"]
    image = np.asarray(Image.open(tmp_path / "out" / "tetra" / "tracer.png"))
    assert image.shape == (512, 512, 3)
    # Corner averaging differs from sampling the pixel centres only where the image changes
    # within a pixel: compare with the committed scene rendered by tracer at pixel centres.
    tracer = pathlib.Path(os.environ.get("TRACER_BIN", ROOT / "build" / "release" / "tracer"))
    centres_png = tmp_path / "centres.png"
    subprocess.run([tracer, ROOT / "scenes" / "spd" / "tetra.scn", "-o", centres_png, "-q"], check=True)
    centres = np.asarray(Image.open(centres_png)).astype(int)
    ours = image.astype(int)
    assert abs(centres.mean() - ours.mean()) < 0.1  # the same picture on average (measured: 0.006)

    def blocks(x):  # means over 4 x 4 pixels: edges within a pixel averaged away
        return x.reshape(128, 4, 128, 4, 3).mean(axis=(1, 3))

    assert np.abs(blocks(centres) - blocks(ours)).mean() < 2  # measured: 1.15 levels
    assert (centres != ours).any()  # and not the same sampling
    report = (tmp_path / "spd.md").read_text()
    assert "| tetra | 0 | 4,096 (4,096) |" in report and (tmp_path / "spd" / "tetra.png").is_file()
