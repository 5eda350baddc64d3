"""The converter's XML loads in Mitsuba and carries camera, shapes and lights over exactly."""

import math
import subprocess
import sys

import numpy as np
import pytest
from conftest import HERE, ROOT

from tracer_tools.xcheck import PeerCannotExpress, ToolError, convert, exact_meshes, mitsuba_render, round_shapes
from tracer_tools.xcheck.lights import light_points

mi = mitsuba_render.mi
ASYMMETRIC = HERE / "asymmetric.scn"
SCENES = sorted((ROOT / "scenes").rglob("*.scn")) + [ASYMMETRIC]


def load(dump, scene_path, tmp_path, *extra):
    scene = dump(scene_path, *extra)
    return scene, mitsuba_render.load(convert.write_mitsuba_scene(scene, tmp_path), scene)


# Committed scenes whose patterns Mitsuba cannot draw (xcheck.mitsuba_textures says which and why).
UNDRAWABLE_PATTERNS = {"globe.scn", "marble_and_wood.scn", "uv_shapes.scn"}


@pytest.mark.parametrize("scene_path", SCENES, ids=lambda p: p.name)
def test_every_scene_loads(dump, tmp_path, scene_path):
    scene = dump(scene_path)
    if scene.get("solids"):  # Mitsuba has no CSG: the check says so, and skips the scene
        with pytest.raises(PeerCannotExpress, match="Mitsuba 3 cannot express"):
            convert.write_mitsuba_scene(scene, tmp_path)
        return
    if any("kind" in light or "fade_distance" in light for light in scene["lights"]):  # spot, parallel, fading
        with pytest.raises(PeerCannotExpress, match="point emitters cannot express"):
            convert.write_mitsuba_scene(scene, tmp_path)
        return
    if scene["render"].get("transparent_shadows") and convert.refracts(scene):
        with pytest.raises(ToolError, match="transparent_shadows"):
            convert.write_mitsuba_scene(scene, tmp_path)
        return
    if scene_path.name in UNDRAWABLE_PATTERNS:  # noise patterns, or (u, v) Mitsuba lays otherwise
        with pytest.raises(ToolError, match="Mitsuba has no texture"):
            convert.write_mitsuba_scene(scene, tmp_path)
        return
    loaded = mitsuba_render.load(convert.write_mitsuba_scene(scene, tmp_path), scene)
    caps = len(round_shapes.disks_of(scene)) - len(
        scene.get("discs", [])
    )  # a capped cone's caps are disks of their own
    assert len(loaded.shapes()) == len(convert.shapes(scene)) + caps
    assert len(loaded.emitters()) == sum(len(light_points(light)) for light in scene["lights"])
    film = loaded.sensors()[0].film()
    assert list(film.size()) == [scene["render"]["width"], scene["render"]["height"]]


def conventions_direction(camera, width, height, x, y):
    """The camera ray through image position (x, y) (pixels, from the top left) by
    conventions.md, in float64."""
    eye, lookat, up = (np.array(camera[k], dtype=float) for k in ("eye", "lookat", "up"))
    w = (eye - lookat) / np.linalg.norm(eye - lookat)
    u = np.cross(up, w) / np.linalg.norm(np.cross(up, w))
    v = np.cross(w, u)
    plane_height = 2 * camera["focal"] * math.tan(math.radians(camera["fovy"]) / 2)
    plane_width = plane_height * width / height
    point = -camera["focal"] * w + (x / width - 0.5) * plane_width * u + (0.5 - y / height) * plane_height * v
    return point / np.linalg.norm(point)


def test_camera_rays_match_the_conventions(dump, tmp_path):
    # Off-axis eye, tilted up vector, 16:9: a mirrored x axis or a horizontal field of view
    # moves these directions by far more than the tolerance.
    scene, loaded = load(dump, ASYMMETRIC, tmp_path)
    sensor, camera = loaded.sensors()[0], scene["camera"]
    width, height = scene["render"]["width"], scene["render"]["height"]
    for x, y in [(0.5, 0.5), (width - 0.5, 0.5), (0.5, height - 0.5), (width / 2, height / 2), (100.5, 20.5)]:
        ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f(x / width, y / height), mi.Point2f(0.5))
        got = np.array(ray.d, dtype=float).ravel()
        np.testing.assert_allclose(got, conventions_direction(camera, width, height, x, y), atol=2e-6)
        origin = np.array(ray.o, dtype=float).ravel()  # moved forward by near_clip = epsilon
        assert np.linalg.norm(origin - camera["eye"]) < 2 * convert.EPSILON


def rotation(axis, angle):
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    radians = math.radians(angle)
    return np.eye(3) + math.sin(radians) * k + (1 - math.cos(radians)) * k @ k


def obj_vertices(path):
    rows = [line.split()[1:4] for line in open(path) if line.startswith("v ")]
    return np.array(rows, dtype=float)


@pytest.mark.parametrize("scene_path", [ASYMMETRIC, ROOT / "scenes" / "bunny_room.scn"], ids=lambda p: p.name)
def test_mesh_vertices_are_placed_scale_rotate_translate(dump, tmp_path, scene_path):
    scene, loaded = load(dump, scene_path, tmp_path)
    mesh = scene["meshes"][0]
    expected = (obj_vertices(mesh["file"]) * mesh["scale"]) @ rotation(**mesh["rotate"]).T + mesh["translate"]
    params = mi.traverse(loaded)
    got = np.array(params["mesh0.vertex_positions"], dtype=float).reshape(-1, 3)
    # Mitsuba renumbers the vertices: match each to its nearest expected one, one to one.
    distances = np.linalg.norm(got[:, None, :] - expected[None, :, :], axis=2)
    nearest = distances.argmin(axis=1)
    assert len(got) == len(expected) and len(set(nearest)) == len(expected)
    assert distances[np.arange(len(got)), nearest].max() < 1e-6


def test_spheres_planes_and_lights_round_trip(dump, tmp_path):
    scene, loaded = load(dump, ASYMMETRIC, tmp_path)
    shapes = {shape.id(): shape for shape in loaded.shapes()}
    for index, sphere in enumerate(scene["spheres"]):
        box = shapes[f"sphere{index}"].bbox()
        np.testing.assert_allclose(np.array(box.center(), dtype=float).ravel(), sphere["center"], atol=1e-6)
        np.testing.assert_allclose(np.array(box.extents(), dtype=float).ravel(), [2 * sphere["radius"]] * 3, atol=1e-6)
    for index, plane in enumerate(scene["planes"]):
        params = mi.traverse(shapes[f"plane{index}"])
        vertices = np.array(params["vertex_positions"], dtype=float).reshape(-1, 3)
        normal = np.array(plane["normal"]) / np.linalg.norm(plane["normal"])
        heights = (vertices - plane["point"]) @ normal
        assert np.abs(heights).max() <= 1e-6 * np.abs(vertices).max()  # every vertex in the plane
        assert np.abs(vertices - vertices[0]).max() >= convert.plane_extent(scene, plane)
    for emitter, light in zip(loaded.emitters(), scene["lights"], strict=False):
        interaction = interaction_at_origin()
        sample, spectrum = emitter.sample_direction(interaction, mi.Point2f(0.0))
        np.testing.assert_allclose(np.array(sample.p, dtype=float).ravel(), light["position"], atol=1e-6)
        colour = np.array(spectrum * sample.dist**2, dtype=float).ravel()
        np.testing.assert_allclose(colour, light["color"], rtol=1e-5)


def interaction_at_origin():
    interaction = mi.Interaction3f()
    interaction.p = mi.Point3f(0.0, 0.0, 0.0)
    interaction.t = mi.Float(0.0)
    return interaction


def test_plain_mitsuba_without_the_plugins_fails_clearly(dump, tmp_path):
    scene = dump(ASYMMETRIC)
    xml_path = convert.write_mitsuba_scene(scene, tmp_path)
    text = xml_path.read_text()
    assert "tools/crosscheck" in text.splitlines()[1]  # the comment says how to render it
    result = subprocess.run(
        [
            sys.executable,
            "-c",
            "import mitsuba as mi; mi.set_variant('scalar_rgb'); " f"mi.load_file({str(xml_path)!r})",
        ],
        capture_output=True,
        text=True,
    )
    assert result.returncode != 0
    assert 'Plugin "tracer_whitted" not found' in result.stderr


def test_area_weighted_normals_weigh_faces_by_area():
    # Vertex 0 is shared by a big triangle in z = 0 and a small one in x = 0.
    positions = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, -1], [0, 1, 0]], dtype=float)
    faces = np.array([[0, 1, 2], [0, 3, 4]])
    normals = exact_meshes.area_weighted_normals(positions, faces)
    big, small = np.array([0, 0, 16.0]), np.array([1.0, 0, 0])  # cross products: 2 x area x normal
    np.testing.assert_allclose(normals[0], (big + small) / np.linalg.norm(big + small))
    np.testing.assert_allclose(normals[1], [0, 0, 1])
    np.testing.assert_allclose(normals[3], [1, 0, 0])


def test_meshes_without_normals_get_area_weighted_ones(dump, tmp_path):
    scene, loaded = load(dump, ROOT / "scenes" / "bunny.scn", tmp_path)
    assert not exact_meshes.obj_normals_used(scene["meshes"][0]["file"])
    params = mi.traverse(loaded)
    positions = np.array(params["mesh0.vertex_positions"], dtype=float).reshape(-1, 3)
    faces = np.array(params["mesh0.faces"]).reshape(-1, 3)
    got = np.array(params["mesh0.vertex_normals"], dtype=float).reshape(-1, 3)
    np.testing.assert_allclose(got, exact_meshes.area_weighted_normals(positions, faces), atol=1e-6)


def test_flat_meshes_use_face_normals_in_mitsuba(dump, tmp_path):
    scene, loaded = load(dump, ROOT / "scenes" / "cubes.scn", tmp_path)
    assert [mesh.get("shading") for mesh in scene["meshes"]] == [None, "flat"]  # the default is left out
    xml = (tmp_path / "scene.xml").read_text()
    assert xml.count('name="face_normals" value="true"') == 1
    params = mi.traverse(loaded)
    assert "mesh0.vertex_normals" in params and params["mesh1.vertex_normals"].shape[0] == 0


def test_file_normals_count_only_when_every_face_names_them(tmp_path):
    # tracer's rule (io/obj_mesh.cpp): vn lines alone are not enough.
    cases = {
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n": True,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\n": True,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1 2 3\n": False,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3//1\n": False,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n": False,
    }
    for index, (text, expected) in enumerate(cases.items()):
        path = tmp_path / f"case{index}.obj"
        path.write_text(text)
        assert exact_meshes.obj_normals_used(path) == expected, text


def test_refraction_is_carried_over_only_where_a_material_transmits(dump, tmp_path):
    glass = dump(ROOT / "scenes" / "glass.scn")
    assert convert.refracts(glass) and not convert.refracts(dump(ROOT / "scenes" / "task2.scn"))
    xml = convert.to_mitsuba_xml(glass)
    assert '<boolean name="refracts" value="true"' in xml
    assert '<float name="ior" value="1.5"' in xml and '<rgb name="kt" value="0.6, 0.9, 0.7"' in xml


def test_flat_shapes_become_mitsubas_own_rectangles_and_cubes(dump):
    scene = dump(ROOT / "scenes" / "room.scn")
    xml = convert.to_mitsuba_xml(scene)
    assert xml.count('type="rectangle"') == len(scene["quads"]) == 102
    assert xml.count('type="cube"') == len(scene["boxes"]) == 6
    assert xml.count('name="flip_normals"') == 1  # the pennant, mirrored by scale (-1, 1, 1)
    # The rectangle's corners (-1, -1), (1, -1), (1, 1), (-1, 1) land on the quad's corners in order.
    quad = {"corner": [1.0, 2.0, 3.0], "edge1": [0.0, 0.0, 2.0], "edge2": [4.0, 0.0, 0.0]}
    matrix = np.array(convert.quad_to_rectangle(quad))
    corner, edge1, edge2 = (np.array(quad[k]) for k in ("corner", "edge1", "edge2"))
    for (x, y), expected in zip(
        ((-1, -1), (1, -1), (1, 1), (-1, 1)),
        (corner, corner + edge1, corner + edge1 + edge2, corner + edge2),
        strict=True,
    ):
        assert np.allclose((matrix @ [x, y, 0, 1])[:3], expected)
    assert np.allclose(matrix[:3, 2], [0, 1, 0])  # the rectangle's normal becomes edge1 x edge2
    box = {"min": [-1.0, 0.0, 2.0], "max": [1.0, 4.0, 3.0]}
    cube = np.array(convert.box_to_cube(box))
    assert np.allclose((cube @ [-1, -1, -1, 1])[:3], box["min"]) and np.allclose((cube @ [1, 1, 1, 1])[:3], box["max"])


@pytest.mark.parametrize(("r0", "r1"), [(1.0, 0.0), (0.0, 2.5), (0.3, 0.7), (0.6, 0.6)])
def test_cone_rings_stay_close_in_radius(r0, r1):
    radii = round_shapes.ring_radii(r0, r1)
    assert radii[0] == r0 and radii[-1] == r1 and len(radii) >= 2
    wide = max(r0, r1)
    for near, far in zip(radii, radii[1:], strict=False):
        small, large = sorted((near, far))
        # Within RING_RATIO of each other, but for the step to a point (below APEX_FRACTION).
        assert large <= small * round_shapes.RING_RATIO * (1 + 1e-12) or small == 0
        assert small > 0 or large <= round_shapes.APEX_FRACTION * wide * (1 + 1e-12)
