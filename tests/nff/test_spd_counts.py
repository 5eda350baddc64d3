"""The SPD's ray counts under `spawn_rules spd` against upstream's published table (its
Readme.txt, copied as tools/tracer_tools/spd/report.py's UPSTREAM_COUNTS): the seven scenes at
their default size, converted with rays through the pixel corners (513 x 513 eye rays), depth 5.
Eye rays that hit within 0.5%, reflection and shadow rays within 1%, refraction rays within 1%
once total internal reflections are counted with them, as upstream's figure counts them
(docs/spd.md). Skipped, with the reason, on a clone without ../shared/spd."""

import json
import os
import pathlib
import subprocess

import pytest

from tracer_tools.spd import steps
from tracer_tools.spd.report import UPSTREAM_COUNTS

ROOT = pathlib.Path(__file__).resolve().parents[2]

NFF = ROOT.parent / "shared" / "spd" / "nff"
TRACER = pathlib.Path(os.environ.get("TRACER_BIN", ROOT / "build" / "release" / "tracer"))

pytestmark = [
    pytest.mark.skipif(not (NFF / "balls.nff").is_file(), reason=f"no SPD scenes at {NFF} (../shared absent)"),
    pytest.mark.skipif(not TRACER.is_file(), reason=f"no tracer at {TRACER}"),
]


def counts(tmp_path: pathlib.Path, name: str) -> dict:
    scene = tmp_path / f"{name}.scn"
    convert = [ROOT / "tools" / "nff2scn", NFF / f"{name}.nff", "-o", scene, "--corner-rays"]
    subprocess.run([str(c) for c in convert], check=True, capture_output=True)
    steps.with_spd_rules(scene, scene)
    stats = tmp_path / "stats.json"
    render = [TRACER, scene, "-o", tmp_path / "image.exr", "-q", "--stats-json", stats]
    subprocess.run([str(c) for c in render], check=True)
    return json.loads(stats.read_text())["rays"]


@pytest.mark.parametrize("name", sorted(UPSTREAM_COUNTS))
def test_counts_under_upstreams_rules_match_its_table(tmp_path: pathlib.Path, name: str):
    hits, reflection, refraction, shadow = UPSTREAM_COUNTS[name]
    rays = counts(tmp_path, name)
    assert rays["primary"] == 513 * 513
    assert rays["primary_hits"] == pytest.approx(hits, rel=0.005)
    assert rays["reflection"] == pytest.approx(reflection, rel=0.01)
    assert rays["shadow"] == pytest.approx(shadow, rel=0.01)
    assert rays["refraction"] + rays["total_internal_reflections"] == pytest.approx(refraction, rel=0.01)
