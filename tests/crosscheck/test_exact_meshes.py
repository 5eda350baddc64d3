"""The meshes in float64 for the integrator's mirror chains (xcheck.exact_meshes): read, placed
and ordered as tracer and Mitsuba have them, and a chain's hit solved on them in float64."""

import numpy as np
import pytest
from conftest import HERE, ROOT
from test_convert import obj_vertices, rotation

from tracer_tools.xcheck import convert, exact_meshes, mitsuba_render

mi = mitsuba_render.mi
ASYMMETRIC = HERE / "asymmetric.scn"
BUNNIES = ROOT / "scenes" / "bunnies.scn"  # 64 blocks share one file: kept in its coordinates


def test_the_reader_takes_every_corner_form_negative_indices_and_polygons(tmp_path):
    path = tmp_path / "forms.obj"
    path.write_text(
        "# corners as v, v/vt, v//vn, v/vt/vn; indices from the end; a pentagon\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\nvt 0 0\nvn 0 0 1\nvn 0 0 -1\n"
        "f 1 2 3\nf 1/1 3/1 4/1\nf 1//2 2//2 3//1\nf -5/1/-1 -4/1/-1 -3/1/-2\nf 1 2 3 4 5\n"
    )
    positions, normals, faces, texcoords = exact_meshes.read_obj(path)
    assert positions.shape == (5, 3) and normals.shape == (2, 3) and texcoords.shape == (1, 2)
    assert [corner[2] for corner in faces[1]] == [0, 0, 0] and faces[0][0][2] == -1
    corners, normal_ids, _ = exact_meshes.fan_triangles(faces)
    assert corners.tolist() == [[0, 1, 2], [0, 2, 3], [0, 1, 2], [0, 1, 2], [0, 1, 2], [0, 2, 3], [0, 3, 4]]
    assert normal_ids[2].tolist() == [1, 1, 0] and normal_ids[3].tolist() == [1, 1, 0]
    assert (normal_ids[[0, 1, 4, 5, 6]] == -1).all()


def test_placement_is_tracers_scale_rotate_translate_and_steps():
    shape = {"scale": [0.5, 0.3, 0.4], "rotate": {"axis": [1, 1, 0], "angle": 40}, "translate": [0.2, -0.4, 1.5]}
    linear, translate = exact_meshes.placement(shape)
    np.testing.assert_allclose(linear, rotation([1, 1, 0], 40) @ np.diag([0.5, 0.3, 0.4]), rtol=0, atol=1e-15)
    np.testing.assert_array_equal(translate, [0.2, -0.4, 1.5])
    # A transform block's steps in order: a translation before a rotation is rotated too.
    steps = {
        "transform": [{"translate": [1, 0, 0]}, {"rotate": {"axis": [0, 0, 1], "angle": 90}}, {"scale": [2, 2, 2]}]
    }
    linear, translate = exact_meshes.placement(steps)
    np.testing.assert_allclose(linear, 2 * rotation([0, 0, 1], 90), atol=1e-15)
    np.testing.assert_allclose(translate, [0, 2, 0], atol=1e-15)


def _placed_tables(dump, tmp_path, scene_path):
    scene = dump(scene_path)
    convert.write_mitsuba_scene(scene, tmp_path)
    return scene, exact_meshes.exact_meshes(scene, tmp_path)


@pytest.mark.parametrize("scene_path", [ASYMMETRIC, ROOT / "scenes" / "room.scn", BUNNIES], ids=lambda p: p.name)
def test_meshes_are_placed_where_tracer_places_them(dump, tmp_path, scene_path):
    scene, (shapes, corners, _) = _placed_tables(dump, tmp_path, scene_path)
    for index, mesh in enumerate(scene["meshes"]):
        first, count, to_object, translate = shapes[f"mesh{index}"]
        assert count == mesh["triangles"]
        placed = corners[first : first + count].reshape(-1, 3) @ np.linalg.inv(to_object).T + translate
        scale = 1.0 + np.abs(mesh["bounds"]).max()
        np.testing.assert_allclose(placed.min(axis=0), mesh["bounds"][0], rtol=0, atol=1e-13 * scale)
        np.testing.assert_allclose(placed.max(axis=0), mesh["bounds"][1], rtol=0, atol=1e-13 * scale)
    if scene_path == BUNNIES:  # one copy of the file's triangles, however many blocks
        bunnies = [
            shapes[f"mesh{i}"][0] for i, mesh in enumerate(scene["meshes"]) if mesh["file"].endswith("bunny.obj")
        ]
        assert len(bunnies) >= 64 and len(set(bunnies)) == 1


def _file_triangles(path):
    faces = [[int(c.split("/")[0]) - 1 for c in line.split()[1:4]] for line in open(path) if line.startswith("f ")]
    return obj_vertices(path)[np.array(faces)]


@pytest.mark.parametrize("scene_path", [ASYMMETRIC, BUNNIES], ids=lambda p: p.name)
def test_a_chains_hit_on_a_mesh_is_solved_in_float64(dump, tmp_path, scene_path):
    scene = dump(scene_path)
    loaded = mitsuba_render.load(convert.write_mitsuba_scene(scene, tmp_path), scene)
    integrator = loaded.integrator()
    # Rays from the eye to random points inside the triangles of the first and the last mesh.
    rng = np.random.default_rng(7)
    eye = np.array(scene["camera"]["eye"], dtype=np.float64)
    targets, expected_planes = [], []
    for mesh in (scene["meshes"][0], scene["meshes"][-1]):
        linear = rotation(**mesh["rotate"]) @ np.diag(np.broadcast_to(mesh["scale"], 3))
        triangles = _file_triangles(mesh["file"]) @ linear.T + mesh["translate"]
        chosen = triangles[rng.integers(len(triangles), size=200)]
        weights = rng.dirichlet([1.0, 1.0, 1.0], size=len(chosen))
        targets.append(np.einsum("tk,tkj->tj", weights, chosen))
        expected_planes.append(chosen)
    targets, chosen = np.concatenate(targets), np.concatenate(expected_planes)
    directions = targets - eye
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    origin = mi.Point3d(*(np.full(len(targets), x) for x in eye))
    direction = mi.Vector3d(*directions.T)
    ray = mi.Ray3f(mi.Point3f(origin), mi.Vector3f(direction))
    si = loaded.ray_intersect(ray)
    point, _, shading, exact = integrator._refine(loaded, si, ray, origin, direction, si.is_valid())
    point, exact = np.array(point, dtype=np.float64).T, np.array(exact)
    mitsuba_point = np.array(si.p, dtype=np.float64).T
    # Where the ray meets the chosen triangle first (not hidden), the point is on its plane in
    # double: within 1e-14 of the scene's size, where Mitsuba's own float32 point is 1e-8 off.
    normals = np.cross(chosen[:, 1] - chosen[:, 0], chosen[:, 2] - chosen[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    unhidden = np.linalg.norm(point - targets, axis=1) < 1e-6
    assert unhidden.sum() > len(targets) // 4 and exact[unhidden].all()
    scale = 1.0 + np.abs(targets).max()

    def off_plane(p):
        return np.abs(np.einsum("tj,tj->t", p - chosen[:, 0], normals))[unhidden]

    assert off_plane(point).max() < 1e-14 * scale
    assert off_plane(mitsuba_point).max() > 1e-9 * scale
    assert np.allclose(np.linalg.norm(np.array(shading, dtype=np.float64).T[unhidden], axis=1), 1.0, atol=1e-15)


def test_mitsuba_pngs_follow_the_scene_s_encoding(tmp_path):
    # tools/mitsuba-render writes what tracer would: the sRGB curve and the sRGB chunk, or neither.
    from PIL import Image

    from tracer_tools.xcheck import images

    linear = np.array([[[0.002, 0.2, 0.8], [0.0, 1.0, 0.35]]], dtype=np.float32)  # no value near a tie
    values = [float(v) for v in linear.reshape(-1)]
    curve = [12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055 for v in values]
    for srgb, expected in ((False, values), (True, curve)):
        path = tmp_path / f"{srgb}.png"
        images.write_png(path, linear, srgb=srgb)
        with Image.open(path) as image:
            image.load()  # checks every chunk's CRC
            assert list(np.asarray(image).reshape(-1)) == [round(255 * v) for v in expected]
        assert (b"sRGB" in path.read_bytes()[:64]) == srgb
