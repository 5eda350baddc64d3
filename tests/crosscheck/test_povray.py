"""The POV-Ray converter's rules (xcheck.povray), without POV-Ray itself."""

import math

import numpy as np
import pytest
from conftest import ROOT

from tracer_tools.xcheck import ToolError, exact_meshes, povray
from tracer_tools.xcheck.lights import light_points


def material(**keys):
    base = {
        "name": "m",
        "ka": [0, 0, 0],
        "kd": [0, 0, 0],
        "ks": [0, 0, 0],
        "km": [0, 0, 0],
        "n": 1,
        "kt": [0, 0, 0],
        "ior": 1,
    }
    return {**base, **keys}


def test_pigment_and_ambient_undo_povrays_scaling_by_opacity():
    text = povray.texture(material(ka=[0.1, 0.1, 0], kd=[0.5, 0.25, 0], kt=[0.5, 0.5, 0.5], ior=1.5))
    # pigment kd / (1 - T), transmit T; ambient ka / kd per channel; a kd of 0 with ka 0 stays 0.
    assert "rgbt <1.0, 0.5, 0.0, 0.5>" in text
    assert "ambient rgb <0.2, 0.4, 0.0>" in text
    assert "interior { ior 1.5 }" in text


def test_ambient_without_diffuse_gets_a_tiny_pigment():
    text = povray.texture(material(ka=[0.1, 0.1, 0.1]))
    assert f"rgbt <{povray.TINY_PIGMENT!r}" in text
    assert f"ambient rgb <{0.1 / povray.TINY_PIGMENT!r}" in text


def test_clear_glass_takes_a_coloured_kt_exactly_and_other_colours_are_noted():
    text = povray.texture(material(ks=[0.6, 0.6, 0.6], n=200, kt=[0.6, 0.9, 0.7], ior=1.33))
    assert "rgbf <0.6, 0.9, 0.7, 1>" in text and "phong 0.6 phong_size 200.0" in text
    assert povray.APPROXIMATED == {}
    povray.texture(material(kd=[0.5, 0.5, 0.5], ks=[0.4, 0.4, 0.3]))
    assert any("coloured ks" in note for note in povray.APPROXIMATED.values())


def test_camera_vectors_span_the_field_of_view(dump):
    scene = dump(ROOT / "scenes" / "task2.scn")
    text = povray.to_povray_sdl(scene)
    camera = next(line for line in text.splitlines() if line.startswith("camera"))
    up = [float(x) for x in camera.split("up <")[1].split(">")[0].split(",")]
    assert math.hypot(*up) == pytest.approx(2 * math.tan(math.radians(scene["camera"]["fovy"]) / 2))
    assert "max_trace_level 5" in text and "adc_bailout 0" in text and "assumed_gamma 1.0" in text


def test_render_times_are_read_from_povrays_statistics():
    log = (
        "  Parse Time:       0 hours  0 minutes  0 seconds (0.019 seconds)\n"
        "  Trace Time:       0 hours  1 minutes  2 seconds (62.125 seconds)\n"
    )
    assert povray.render_times(log) == {"parse_seconds": 0.019, "trace_seconds": 62.125}


def test_patterns_povray_cannot_express_are_refused_with_a_reason():
    placed = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]
    base = {"name": "", "ks": [0, 0, 0], "km": [0, 0, 0], "n": 1, "kt": [0, 0, 0], "ior": 1}
    marble = {
        "pattern": "marble",
        "mapping": "solid",
        "to_pattern": placed,
        "colors": [[0, [1, 1, 1]]],
        "axis": [1, 0, 0],
        "turbulence": 1,
        "octaves": 6,
    }
    uv = {"pattern": "checker", "mapping": "uv", "to_pattern": placed, "even": [1, 1, 1], "odd": [0, 0, 0]}
    solid = dict(uv, mapping="solid")
    for kd, ka, why in ((marble, [0, 0, 0], "noise"), (uv, [0, 0, 0], "mapping uv"), (solid, [0.1, 0.1, 0.1], "ka")):
        with pytest.raises(ToolError, match=why):
            povray.texture({**base, "kd": kd, "ka": ka})
    # ka the same checker scaled: POV-Ray's ambient, per channel.
    dim = dict(solid, even=[0.1, 0.1, 0.1], odd=[0, 0, 0])
    text = povray.texture({**base, "kd": solid, "ka": dim})
    assert "ambient rgb <0.1, 0.1, 0.1>" in text and "checker" in text and "matrix <1.0, 0.0, 0.0," in text


def test_uv_mapping_on_a_mesh_is_povrays_uv_mapping_given_tracers_uv(tmp_path):
    """A uv pattern on a mesh2 becomes POV-Ray's uv_mapping over uv_vectors carrying tracer's
    (u, v) (an OBJ's vt, fanned as its faces are); on other shapes it is refused."""
    obj = tmp_path / "square.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n")
    uvs = exact_meshes._triangles(obj, np.eye(3), np.zeros(3), False)[2]
    assert uvs.tolist() == [[[0, 0], [0.5, 0], [0.5, 1]], [[0, 0], [0.5, 1], [0, 1]]]
    (tmp_path / "partial.obj").write_text(obj.read_text() + "v 0 0 1\nf 1 2 5\n")
    partial = exact_meshes._triangles(tmp_path / "partial.obj", np.eye(3), np.zeros(3), False)[2]
    assert not partial.any()  # tracer's (0, 0) then
    placed = [[2.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]
    image = {"pattern": "image", "mapping": "uv", "to_pattern": placed, "file": "grid.png", "wrap": "repeat"}
    corners = np.array([[[0, 0, 0], [1, 0, 0], [1, 1, 0]]], dtype=np.float64)
    text = povray._mesh2(corners, np.zeros_like(corners), material(kd=image), uvs[:1])
    assert "uv_vectors { 3,\n    <0.0, 0.0>, <0.5, 0.0>, <0.5, 1.0>" in text and "uv_indices { 1," in text
    assert "pigment { uv_mapping image_map" in text and "matrix <0.5, 0.0, 0.0," in text
    with pytest.raises(ToolError, match="mapping uv on a shape"):
        povray.texture(material(kd=image))


def test_solids_nest_as_povrays_csg_with_one_interior():
    glass = material(kt=[0.9, 0.9, 0.9], km=[0.1, 0.1, 0.1], ior=1.5)
    sphere = {"center": [0, 0, 0], "radius": 1, "material": glass}
    box = {"min": [-1, -1, -1], "max": [1, 1, 1], "translate": [1, 0, 0], "material": glass}
    solids = [
        {"op": "difference", "nested": False, "parts": [{"kind": "box", "box": box}, {"kind": "solid", "solid": 1}]},
        {"op": "union", "nested": True, "parts": [{"kind": "sphere", "sphere": sphere}] * 2},
    ]
    text = povray._solid(solids, 0)
    lines = text.splitlines()
    assert lines[0] == "difference {" and lines[2] == "merge {" and lines[-1] == "}"
    assert "matrix <1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0>" in lines[1]
    # One interior, the whole solid's, just before its closing brace; none on the parts.
    assert text.count("interior") == 1 and lines[-2] == "interior { ior 1.5 }"
    water = {**sphere, "material": material(kt=[0.9, 0.9, 0.9], ior=1.33)}
    solids[1]["parts"] = [{"kind": "sphere", "sphere": water}]
    with pytest.raises(ToolError, match="different ior"):
        povray._solid(solids, 0)


def test_a_mesh_in_a_solid_is_a_mesh2_with_an_inside_and_the_solids_interior():
    glass = material(kt=[0.9, 0.9, 0.9], ior=1.5)
    cube = {"file": str(ROOT / "scenes" / "meshes" / "cube.obj"), "scale": [2, 2, 2], "material": glass}
    sphere = {"center": [0, 1, 0], "radius": 0.5, "material": glass}
    solids = [
        {
            "op": "difference",
            "nested": False,
            "parts": [{"kind": "mesh", "mesh": cube}, {"kind": "sphere", "sphere": sphere}],
        }
    ]
    text = povray._solid(solids, 0)
    lines = text.splitlines()
    assert lines[0] == "difference {" and lines[1] == "mesh2 {" and "face_indices { 12," in text
    # POV-Ray needs the inside_vector to know a mesh's inside; the interior is the solid's alone.
    assert "  inside_vector <0, 0, 1>" in lines and text.count("interior") == 1 and lines[-2] == "interior { ior 1.5 }"


def test_an_area_light_is_written_as_its_samples():
    """POV-Ray's own area_light shades with the whole light times the fraction of samples
    unblocked; tracer's samples are point lights each, so the converter writes them so."""
    light = {"position": [0, 4, 0], "color": [0.8, 0.8, 0.8], "edge1": [2, 0, 0], "edge2": [0, 0, 1], "samples": [3, 2]}
    points = light_points(light)
    assert len(points) == 6
    assert points[0][0] == [-1.0, 4.0, -0.5] and points[0][1] == pytest.approx([0.8 / 6] * 3)
    assert points[-1][0] == [1.0, 4.0, 0.5]
    assert light_points({"position": [1, 2, 3], "color": [1, 1, 1]}) == [([1, 2, 3], [1, 1, 1])]
