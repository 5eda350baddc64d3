"""The SPD generators written in the scene language (scenes/spd/procedural/) against the
generators themselves: the same objects in the same order, every coordinate within 1e-9
relative, at sizes 1 to 3. The generators are built from ../shared/spd/src with their NFF
written at full precision (%.17g where they print %g: six digits would hide any difference
below 5e-6), converted by tools/nff2scn and read back with tracer --dump-json. Skipped, with
the reason, on a clone without ../shared/spd."""

import json
import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPD = ROOT.parent / "shared" / "spd"
TRACER = pathlib.Path(os.environ.get("TRACER_BIN", ROOT / "build" / "release" / "tracer"))
PROCEDURAL = ROOT / "scenes" / "spd" / "procedural"
TOLERANCE = 1e-9

pytestmark = [
    pytest.mark.skipif(not (SPD / "src" / "balls.c").is_file(), reason=f"no SPD sources at {SPD} (../shared absent)"),
    pytest.mark.skipif(not TRACER.is_file(), reason=f"no tracer at {TRACER}"),
]


@pytest.fixture(scope="module")
def generators(tmp_path_factory: pytest.TempPathFactory) -> pathlib.Path:
    """The balls, tetra, rings and tree generators, built as ../shared/spd/build.sh builds them
    but printing every number at full precision."""
    folder = tmp_path_factory.mktemp("spd")
    for source in (SPD / "src").iterdir():
        if source.suffix in (".c", ".h") or source.name == "makefile":
            shutil.copy(source, folder / source.name)
    for printer in folder.glob("lib*.c"):
        printer.write_text(printer.read_text(encoding="latin-1").replace("%g", "%.17g"), encoding="latin-1")
    compiler = "cc -O2 -w -std=gnu89 -include compat.h"
    subprocess.run(
        ["make", "-s", "-C", folder, f"CC={compiler}", "balls", "tetra", "rings", "tree"],
        check=True,
        capture_output=True,
    )
    return folder


def dump(scene: pathlib.Path, *options: str) -> dict:
    done = subprocess.run([TRACER, "--dump-json", scene, *options], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def converted(generators: pathlib.Path, name: str, size: int, folder: pathlib.Path) -> pathlib.Path:
    nff = folder / f"{name}{size}.nff"
    with open(nff, "w") as out:
        subprocess.run([generators / name, "-s", str(size)], check=True, stdout=out)
    scene = folder / f"{name}{size}.scn"
    done = subprocess.run([ROOT / "tools" / "nff2scn", nff, "-o", scene], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return scene


def assert_close(ours: list, theirs: list, what: str) -> None:
    assert len(ours) == len(theirs), what
    for a, b in zip(ours, theirs, strict=False):
        # Relative to the numbers' own size, with the scene's unit as the floor (a coordinate
        # that is 0 in one and 1e-17 in the other is the same).
        assert abs(a - b) <= TOLERANCE * max(abs(a), abs(b), 1.0), f"{what}: {ours} against {theirs}"


def assert_same_view(ours: dict, theirs: dict) -> None:
    for key in ("eye", "lookat", "up"):
        assert_close(ours["camera"][key], theirs["camera"][key], f"camera {key}")
    assert len(ours["lights"]) == len(theirs["lights"])
    for mine, upstream in zip(ours["lights"], theirs["lights"], strict=False):
        assert_close(mine["position"], upstream["position"], "light position")


@pytest.mark.parametrize("size", [1, 2, 3])
def test_balls_is_the_generators_sphereflake(generators: pathlib.Path, tmp_path: pathlib.Path, size: int):
    theirs = dump(converted(generators, "balls", size, tmp_path))
    ours = dump(PROCEDURAL / "balls.scn", "-D", f"size={size}")
    assert len(ours["spheres"]) == len(theirs["spheres"]) == sum(9**k for k in range(size + 1))
    for index, (mine, upstream) in enumerate(zip(ours["spheres"], theirs["spheres"], strict=False)):
        assert_close(mine["center"] + [mine["radius"]], upstream["center"] + [upstream["radius"]], f"sphere {index}")
    assert_same_view(ours, theirs)
    # The floor: one square polygon (a mesh of it) against one quad, over the same corners.
    (floor,) = ours["quads"]
    corners = [floor["corner"], [c + e for c, e in zip(floor["corner"], floor["edge1"], strict=False)]]
    corners.append([c + e for c, e in zip(corners[1], floor["edge2"], strict=False)])
    low = [min(p[axis] for p in corners) for axis in range(3)]
    high = [max(p[axis] for p in corners) for axis in range(3)]
    (mesh,) = theirs["meshes"]
    assert_close(low + high, mesh["bounds"][0] + mesh["bounds"][1], "floor")


def obj_triangles(path: pathlib.Path) -> list:
    """The triangles of an OBJ file nff2scn wrote, in order, as 9 numbers each."""
    vertices, triangles = [], []
    for line in path.read_text().splitlines():
        words = line.split()
        if words and words[0] == "v":
            vertices.append([float(w) for w in words[1:4]])
        elif words and words[0] == "f":
            corners = [vertices[int(w.split("/")[0]) - 1] for w in words[1:]]
            assert len(corners) == 3
            triangles.append([c for corner in corners for c in corner])
    return triangles


@pytest.mark.parametrize("size", [1, 2, 3])
def test_tetra_is_the_generators_tetrahedron(generators: pathlib.Path, tmp_path: pathlib.Path, size: int):
    scene = converted(generators, "tetra", size, tmp_path)
    theirs = dump(scene)
    ours = dump(PROCEDURAL / "tetra.scn", "-D", f"size={size}")
    (mesh,) = theirs["meshes"]
    upstream = obj_triangles(pathlib.Path(mesh["file"]))
    assert len(ours["triangles"]) == len(upstream) == 4**size
    for index, (mine, their) in enumerate(zip(ours["triangles"], upstream, strict=False)):
        assert_close(mine["a"] + mine["b"] + mine["c"], their, f"triangle {index}")
    assert_same_view(ours, theirs)


@pytest.mark.parametrize(
    ("name", "size", "count"), [("rings", 1, 30), ("rings", 3, 420), ("tree", 1, 3), ("tree", 3, 15)]
)
def test_rings_and_tree_are_the_generators_cones_and_spheres(
    generators: pathlib.Path, tmp_path: pathlib.Path, name: str, size: int, count: int
):
    """Each open cone (a cylinder in rings) and sphere, in the generator's order."""
    theirs = dump(converted(generators, name, size, tmp_path))
    ours = dump(PROCEDURAL / f"{name}.scn", "-D", f"size={size}")
    assert len(ours["cones"]) == len(theirs["cones"]) == len(ours["spheres"]) == len(theirs["spheres"]) == count
    for index, (mine, upstream) in enumerate(zip(ours["cones"], theirs["cones"], strict=True)):
        assert mine["caps"] is upstream["caps"] is False
        numbers = [*mine["base"], *mine["top"], mine["base_radius"], mine["top_radius"]]
        assert_close(
            numbers,
            [*upstream["base"], *upstream["top"], upstream["base_radius"], upstream["top_radius"]],
            f"cone {index}",
        )
    for index, (mine, upstream) in enumerate(zip(ours["spheres"], theirs["spheres"], strict=True)):
        assert_close(mine["center"] + [mine["radius"]], upstream["center"] + [upstream["radius"]], f"sphere {index}")
    assert_same_view(ours, theirs)
