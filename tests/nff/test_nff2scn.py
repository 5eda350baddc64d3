"""tools/nff2scn on small hand-written NFF files: every entity, the conventions, and the errors."""

import math
import os
import pathlib
import subprocess
import sys
import tempfile

import numpy as np
import pytest

from tracer_tools.nff import convert, geometry, nff2scn, reader

ROOT = pathlib.Path(__file__).resolve().parents[2]


VIEW = """v
from 0 0 0
at 0 0 -1
up 0 1 0
angle 40
hither 0.01
resolution 11 11
"""


def tracer_bin():
    return pathlib.Path(os.environ.get("TRACER_BIN", ROOT / "build" / "release" / "tracer"))


def run_nff2scn(tmp_path, text, *options, name="scene"):
    """Writes text to tmp_path/NAME.nff and converts it; returns (CompletedProcess, scn path)."""
    source = tmp_path / f"{name}.nff"
    source.write_text(text)
    output = tmp_path / f"{name}.scn"
    environment = {**os.environ, "PYTHONPATH": str(ROOT / "tools")}
    done = subprocess.run(
        [sys.executable, "-m", "tracer_tools.nff.nff2scn", str(source), "-o", str(output), *options],
        capture_output=True,
        text=True,
        env=environment,
    )
    return done, output


class Converted:
    """What nff2scn wrote for an NFF text: the .scn text and the OBJ files by name."""

    def __init__(self, text, corner_rays=False, cones="analytic"):
        with tempfile.TemporaryDirectory() as folder:
            source, output = pathlib.Path(folder) / "test.nff", pathlib.Path(folder) / "test.scn"
            source.write_text(text)
            self.summary = nff2scn.convert_file(source, output, corner_rays, cones=cones)
            self.scn = output.read_text()
            self.meshes = {path.name: path.read_text() for path in (output.parent / "test_meshes").iterdir()}


def convert_text(text, corner_rays=False, cones="analytic"):
    return None, Converted(text, corner_rays, cones)


def block_lines(scn, kind):
    return [line for line in scn.splitlines() if line.startswith(kind + " ")]


def obj_arrays(text):
    """(vertices, normals, faces as (vertex, normal) index lists, 0-based) of OBJ text."""
    vertices, normals, faces = [], [], []
    for line in text.splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "v":
            vertices.append([float(w) for w in words[1:4]])
        elif words[0] == "vn":
            normals.append([float(w) for w in words[1:4]])
        elif words[0] == "f":
            faces.append([tuple(int(i) - 1 for i in corner.split("//")) for corner in words[1:]])
    return np.array(vertices), np.array(normals), faces


# ---------------------------------------------------------------------------- entities
def test_view_angle_spans_the_centres_of_the_outer_rows():
    scene, converted = convert_text(VIEW + "f 1 1 1 1 0 1 0 0\ns 0 0 -5 1\n")
    (render,) = block_lines(converted.scn, "render")
    assert "width 11" in render and "height 11" in render and "max_depth 4" in render
    (camera,) = block_lines(converted.scn, "camera")
    fovy = float(camera.split("fovy ")[1].split()[0])
    # 11 rows: the outer centres are 5 pixels from the middle, the edges 5.5.
    assert math.tan(math.radians(fovy) / 2) == pytest.approx(math.tan(math.radians(20)) * 11 / 10, rel=1e-8)
    assert "eye (0, 0, 0)" in camera and "lookat (0, 0, -1)" in camera and "up (0, 1, 0)" in camera


def test_corner_rays_put_pixel_centres_on_the_corners():
    _, converted = convert_text(VIEW + "f 1 1 1 1 0 1 0 0\ns 0 0 -5 1\n", corner_rays=True)
    (render,) = block_lines(converted.scn, "render")
    assert "width 12" in render and "height 12" in render
    (camera,) = block_lines(converted.scn, "camera")
    fovy = float(camera.split("fovy ")[1].split()[0])
    # 12 rows whose centres are the 11-pixel image's corners, 5.5 pixels out, edges at 6.
    assert math.tan(math.radians(fovy) / 2) == pytest.approx(math.tan(math.radians(20)) * 12 / 10, rel=1e-8)


def test_background_and_lights_with_and_without_colour():
    text = VIEW + "b 0.1 0.2 0.3\nl 1 2 3\nl 4 5 6 1 0.5 0\nf 1 1 1 1 0 1 0 0\ns 0 0 -5 1\n"
    _, converted = convert_text(text)
    assert "background (0.1, 0.2, 0.3)" in block_lines(converted.scn, "render")[0]
    lights = block_lines(converted.scn, "light")
    intensity = math.sqrt(2) / 4  # sqrt(L) / (2L) for L = 2
    assert lights[0] == f"light {{ position (1, 2, 3)  color {intensity!r} }}"
    assert lights[1] == f"light {{ position (4, 5, 6)  color ({intensity!r}, {intensity / 2!r}, 0) }}"


def test_fill_maps_to_phong_mirror_and_glass():
    text = VIEW + "l 0 5 0\nf 1 0.5 0.25 0.8 0.3 20 0 0\ns 0 0 -5 1\nf 1 1 1 0.1 0.2 50 0.9 1.5\ns 2 0 -5 1\n"
    _, converted = convert_text(text)
    materials = block_lines(converted.scn, "material")
    # One light: intensity 0.5, ambient 0.5 * Kd * colour.
    assert materials[0] == "material m0 { ka (0.4, 0.2, 0.1)  kd (0.8, 0.4, 0.2)  ks 0.3  n 20  km 0.3 }"
    assert materials[1] == "material m1 { ka 0.05  kd 0.1  ks 0.2  n 50  km 0.2  kt 0.9  ior 1.5 }"
    spheres = block_lines(converted.scn, "sphere")
    assert spheres == [
        "sphere { center (0, 0, -5)  radius 1  material m0 }",
        "sphere { center (2, 0, -5)  radius 1  material m1 }",
    ]


def test_polygon_non_convex_is_triangulated_with_its_winding():
    # An L-shaped hexagon, counter-clockwise seen from +z: 4 triangles covering area 3.
    text = VIEW + "f 1 1 1 1 0 1 0 0\np 6\n0 0 -5\n2 0 -5\n2 1 -5\n1 1 -5\n1 2 -5\n0 2 -5\n"
    _, converted = convert_text(text)
    (mesh,) = block_lines(converted.scn, "mesh")
    assert 'file "test_meshes/polygons-m0.obj"' in mesh
    vertices, normals, faces = obj_arrays(converted.meshes["polygons-m0.obj"])
    assert len(faces) == 4 and normals.tolist() == [[0, 0, 1]]
    area = 0.0
    for face in faces:
        a, b, c = (vertices[v] for v, _ in face)
        cross = np.cross(b - a, c - a)
        assert cross[2] > 0  # every triangle faces +z, as the polygon does
        area += cross[2] / 2
    assert area == pytest.approx(3.0)


def test_patch_keeps_its_corner_normals():
    text = VIEW + "f 1 1 1 1 0 1 0 0\npp 3\n0 0 -5 0 0 1\n1 0 -5 0 0.6 0.8\n0 1 -5 0.6 0 0.8\n"
    _, converted = convert_text(text)
    vertices, normals, faces = obj_arrays(converted.meshes["polygons-m0.obj"])
    assert faces == [[(0, 0), (1, 1), (2, 2)]]
    assert normals.tolist() == [[0, 0, 1], [0, 0.6, 0.8], [0.6, 0, 0.8]]


def test_cone_is_an_open_analytic_cone():
    text = VIEW + "f 1 1 1 1 0 1 0 0\nc 0 -1 -5 0.5 0 1 -5 0.25\nc\n1 -1 -5 -0.5\n1 1 -5 -0.5\n"
    _, converted = convert_text(text)
    cones = block_lines(converted.scn, "cone")
    assert cones == [
        "cone { base (0, -1, -5)  top (0, 1, -5)  base_radius 0.5  top_radius 0.25  caps false  material m0 }",
        "cone { base (1, -1, -5)  top (1, 1, -5)  base_radius 0.5  top_radius 0.5  caps false  material m0 }",
    ]
    assert converted.meshes == {}


def test_cone_as_mesh_is_an_instance_of_a_unit_frustum():
    text = VIEW + "f 1 1 1 1 0 1 0 0\nc 0 -1 -5 0.5 0 1 -5 0.25\nc\n1 -1 -5 0.5\n1 1 -5 0.25\n"
    _, converted = convert_text(text, cones="mesh")
    meshes = block_lines(converted.scn, "mesh")
    assert len(meshes) == 2 and len(converted.meshes) == 1  # one unit mesh for both (same ratio)
    (name,) = converted.meshes
    assert name == "cone-0.5.obj"
    assert "scale (0.5, 0.5, 2)" in meshes[0] and "translate (0, -1, -5)" in meshes[0]
    assert "axis (-1, 0, 0) angle 90" in meshes[0]  # +z turned onto +y


def test_cones_past_the_unit_mesh_limit_are_tessellated_in_place(monkeypatch):
    monkeypatch.setattr(convert, "MAX_CONE_MESHES", 1)
    text = VIEW + "f 1 1 1 1 0 1 0 0\nc 0 -1 -5 0.5 0 1 -5 0.25\nc 1 -1 -5 0.5 1 1 -5 0.1\n"
    _, converted = convert_text(text, cones="mesh")
    assert sorted(converted.meshes) == ["cone-0.5.obj", "polygons-m0.obj"]
    vertices, normals, faces = obj_arrays(converted.meshes["polygons-m0.obj"])
    # The second cone (ratio 0.2) in world space: its base ring around (1, -1, -5), radius >= 0.5.
    base = vertices[np.isclose(vertices[:, 1], -1)]
    assert len(base) >= geometry.LEAST_SIDES
    assert np.hypot(base[:, 0] - 1, base[:, 2] + 5) == pytest.approx(0.5, rel=0.02)
    assert np.allclose(np.linalg.norm(normals, axis=1), 1)


def test_too_many_materials_is_an_error_at_the_shape(tmp_path, monkeypatch):
    monkeypatch.setattr(convert, "MAX_MATERIALS", 1)
    source = tmp_path / "scene.nff"
    source.write_text(VIEW + "f 1 1 1 1 0 1 0 0\ns 0 0 -5 1\nf 1 0 0 1 0 1 0 0\ns 1 0 -5 1\n")
    with pytest.raises(reader.NffError) as error:
        nff2scn.convert_file(source, tmp_path / "scene.scn")
    assert ":11:1: error: more than 1 different surfaces" in str(error.value)
    assert [path.name for path in tmp_path.iterdir()] == ["scene.nff"]  # no output, no staging left


@pytest.mark.parametrize("ratio", [1.0, 0.5, 0.0])
def test_frustum_facets_straddle_the_true_surface(ratio):
    sides = 40
    vertices, normals, faces = obj_arrays(geometry.frustum_mesh(ratio, sides))
    for z, radius in ((0.0, 1.0), (1.0, ratio)):
        ring = vertices[np.isclose(vertices[:, 2], z)]
        corner = np.hypot(ring[:, 0], ring[:, 1])
        midpoint = np.hypot(*(ring[:, :2] + np.roll(ring[:, :2], -1, axis=0)).T / 2)
        deviation = radius * math.tan(math.pi / (2 * sides)) ** 2
        assert corner == pytest.approx(radius + deviation, abs=1e-8)
        if radius > 0:
            assert midpoint == pytest.approx(radius - deviation, abs=1e-8)
    # Normals are the true cone's: perpendicular to the slanted side.
    assert np.allclose(np.linalg.norm(normals, axis=1), 1)
    assert np.allclose(normals[:, 2] / np.hypot(normals[:, 0], normals[:, 1]), 1 - ratio)


def test_sides_meet_the_pixel_bound():
    radius, depth, pixels_per_unit = 0.5, 3.0, 600.0
    sides = geometry.segments_for_error(radius, depth, pixels_per_unit, 0.1)
    error_pixels = radius * math.tan(math.pi / (2 * sides)) ** 2 * pixels_per_unit / depth
    fewer = radius * math.tan(math.pi / (2 * (sides - 1))) ** 2 * pixels_per_unit / depth
    assert error_pixels <= 0.1 < fewer


def test_frame_to_axis_turns_z_onto_any_direction():
    for direction in ([0, 0, 1], [0, 0, -1], [1, 2, 3], [0, -1, 0]):
        d = np.array(direction, dtype=float) / np.linalg.norm(direction)
        axis, angle = geometry.frame_to_axis(d)
        k, theta = np.array(axis), math.radians(angle)
        z = np.array([0.0, 0.0, 1.0])
        turned = z * math.cos(theta) + np.cross(k, z) * math.sin(theta) + k * np.dot(k, z) * (1 - math.cos(theta))
        assert turned == pytest.approx(d, abs=1e-12)


# ---------------------------------------------------------------------------- errors
@pytest.mark.parametrize(
    "text, where, message",
    [
        (VIEW + "f 1 1 1 1 0 1 0 0\ns 0 0 x 1\n", "9:7", "expected the sphere's centre (z), found 'x'"),
        (VIEW + "f 1 1 1 1 0 1 0 0\ns 0 0 -5 nan\n", "9:10", "must be a finite number"),
        (VIEW + "q 1 2 3\n", "8:1", "unknown NFF entity 'q'"),
        (VIEW + "s 0 0 -5 1\n", "8:1", "a shape before any 'f' line"),
        (VIEW + "f 1 1 1 1 0 1 0 0\np 2\n0 0 0\n1 0 0\n", "9:3", "from 3 to 100,000"),
        (VIEW + "f 1 1 1 1 0 1 0 0\np 3\n0 0 0\n1 0 0\n", "11:6", "found the end of the file"),
        (VIEW + "f 1 1 1 1 0 1 0.5 0\n", "8:1", "needs an index of refraction > 0"),
        # tracer refuses km and kt above 1: refused here, not in the scene written.
        (VIEW + "f 1 1 1 1 1.5 1 0 0\ns 0 0 -5 1\n", "8:1", "Ks (the mirror weight) must be at most 1, found 1.5"),
        (VIEW + "f 1 1 1 1 0 1 2 1.5\ns 0 0 -5 1\n", "8:1", "T (transmittance) must be at most 1, found 2"),
        ("f 1 1 1 1 0 1 0 0\ns 0 0 -5 1\n", "2:1", "a shape before the view"),
        ("b 0 0 0\n", "1:8", "no view"),
        (VIEW.replace("angle 40", "angle 180"), "1:1", "between 0 and 180 degrees"),
        (VIEW.replace("11 11", "1 11"), "7:12", "from 2 to 16,384"),
        (VIEW + "f 1 1 1 1 0 1 0 0\nc 0 0 0 1 0 0 0 1\n", "9:1", "the same point"),
        (VIEW + "f 1 1 1 1 0 1 0 0\ns 1_0 0 -5 1\n", "9:3", "found '1_0'"),
        (VIEW + "f 1 1 1 1 0 1 0 0\n" + ("p 100000\n" + "0 0 0\n" * 100000) * 2 + "p 9\n", "200011:1", "too large"),
    ],
)
def test_errors_name_file_line_and_column(tmp_path, text, where, message):
    done, output = run_nff2scn(tmp_path, text)
    assert done.returncode == 1, done.stderr
    first = done.stderr.splitlines()[0]
    assert first.startswith(f"{tmp_path / 'scene.nff'}:{where}: error: "), done.stderr
    assert message in first
    assert "^" in done.stderr.splitlines()[2]
    assert not output.exists() and not (tmp_path / "scene_meshes").exists()


def test_lone_carriage_returns_end_lines_and_long_lines_are_windowed(tmp_path):
    text = (VIEW + "f 1 1 1 1 0 1 0 0\n").replace("\n", "\r") + "s 0 0 -5 1" + " " * 5000 + "x\r"
    done, _ = run_nff2scn(tmp_path, text)
    first, shown, caret = done.stderr.splitlines()[:3]
    assert first.startswith(f"{tmp_path / 'scene.nff'}:9:5011: error: unknown NFF entity 'x'"), first
    assert len(shown) < 200 and shown[len(caret) - 1] == "x"


def test_warnings_are_capped(tmp_path):
    done, output = run_nff2scn(tmp_path, VIEW + "f 1 1 1 1 0 1 0 0\n" + "p 3\n0 0 0\n1 1 1\n2 2 2\n" * 100)
    assert done.returncode == 0 and output.exists()
    assert done.stderr.count(": warning: a polygon without area") == convert.MAX_WARNINGS
    assert "80 more warnings not shown" in done.stderr


def test_errors_are_capped_and_each_reported(tmp_path):
    text = VIEW + "f 1 1 1 1 0 1 0 0\n" + "s 0 0 x 1\n" * 50
    done, _ = run_nff2scn(tmp_path, text)
    assert done.returncode == 1
    assert done.stderr.count(": error: ") == reader.MAX_ERRORS
    assert "stopped after 20 errors" in done.stderr


def test_a_fifo_is_refused_without_waiting_for_a_writer(tmp_path):
    fifo = tmp_path / "scene.nff"
    os.mkfifo(fifo)
    environment = {**os.environ, "PYTHONPATH": str(ROOT / "tools")}
    done = subprocess.run(
        [sys.executable, "-m", "tracer_tools.nff.nff2scn", str(fifo), "-o", str(tmp_path / "x.scn")],
        capture_output=True,
        text=True,
        env=environment,
        timeout=60,
    )
    assert done.returncode != 0 and "not a regular file" in done.stderr


def test_a_failed_conversion_keeps_the_previous_output(tmp_path):
    done, output = run_nff2scn(tmp_path, VIEW + "l 0 5 0\nf 1 1 1 1 0 1 0 0\ns 0 0 -5 1\n")
    assert done.returncode == 0, done.stderr
    before = output.read_text()
    done, _ = run_nff2scn(tmp_path, VIEW + "s 0 0 -5 1\n")
    assert done.returncode == 1 and output.read_text() == before


# ---------------------------------------------------------------------------- with tracer
def render_rows(scn, tmp_path):
    """The rendered image of a scene as an array (rows, columns, RGB) in [0, 1]."""
    oiio = pytest.importorskip("PIL.Image")
    image = tmp_path / "out.png"
    subprocess.run([tracer_bin(), str(scn), "-o", str(image), "-q"], check=True)
    return np.asarray(oiio.open(image)).astype(float) / 255


def test_every_entity_converts_to_a_scene_tracer_renders(tmp_path):
    if not tracer_bin().is_file():
        pytest.skip(f"no tracer at {tracer_bin()}")
    text = (
        VIEW
        + "b 0 0 0.2\nl 0 5 0\nl 1 5 1 0.5 0.5 1\nf 1 0 0 1 0.5 10 0 0\ns -1 0 -6 0.5\n"
        + "f 0 1 0 1 0 1 0.5 1.3\np 4\n-3 -1 -8\n3 -1 -8\n3 -1 -2\n-3 -1 -2\n"
        + "pp 3\n0 0 -7 0 0 1\n1 0 -7 0 0 1\n0 1 -7 0 0 1\nc 1 -1 -6 0.3 1 0 -6 0.1\n"
    )
    done, scn = run_nff2scn(tmp_path, text)
    assert done.returncode == 0, done.stderr
    check = subprocess.run([tracer_bin(), "--check", str(scn)], capture_output=True, text=True)
    assert check.returncode == 0, check.stderr
    image = render_rows(scn, tmp_path)
    assert image.shape == (11, 11, 3)


def test_the_view_angle_reaches_the_centres_of_the_outer_pixels(tmp_path):
    """Tiny spheres 20 degrees above and below the view axis (angle 40) are seen by the rays
    through the middle pixels of the top and bottom rows, and not by their neighbours."""
    if not tracer_bin().is_file():
        pytest.skip(f"no tracer at {tracer_bin()}")
    distance, tangent = 10.0, math.tan(math.radians(20))
    spheres = "".join(f"s 0 {sign * distance * tangent:.9g} {-distance} 0.02\n" for sign in (1, -1))
    done, scn = run_nff2scn(tmp_path, VIEW + "l 0 0 0\nf 1 1 1 1 0 1 0 0\n" + spheres)
    assert done.returncode == 0, done.stderr
    image = render_rows(scn, tmp_path)
    lit = image.sum(axis=2) > 0
    assert lit[0, 5] and lit[10, 5]
    assert lit.sum() == 2
