"""tools/crosscheck end to end, at reduced resolution, and the error figures it reports."""

import json
import os
import re
import shutil
import subprocess

import numpy as np
import pytest
from conftest import HERE, ROOT, run_tool

from tracer_tools.xcheck import metrics
from tracer_tools.xcheck.images import read_exr

SMALL = ["--width", "300"]  # 300 x 200 for the 1200 x 800 scenes


@pytest.mark.parametrize("scene", ["task2", "bunny", "glass", "cubes", "room"])
def test_tracer_and_mitsuba_agree_at_reduced_resolution(tracer_bin, tmp_path, scene):
    result = run_tool(
        "crosscheck",
        ROOT / "scenes" / f"{scene}.scn",
        *SMALL,
        "--out",
        tmp_path,
        "--max-over-2",
        "0.1",
        "--max-over-8",
        "0.05",
        "--json",
    )
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert (report["width"], report["samples"]) == (300, 1)  # the height keeps the scene's aspect ratio
    assert report["over_2"] <= 0.001 and report["psnr"] > 60
    for name in ("tracer.png", "mitsuba.png", "heatmap.png", "side_by_side.png", "scene.xml", "report.json"):
        assert (tmp_path / name).is_file(), name


@pytest.mark.parametrize(
    ("scene", "edit"),
    [
        (ROOT / "scenes" / "textured_vase.scn", ("", "")),
        (ROOT / "scenes" / "whitted1980.scn", ("transparent_shadows true", "transparent_shadows false")),
        (HERE / "uv_spheres.scn", ("", "")),
    ],
    ids=lambda value: value.stem if hasattr(value, "stem") else "",
)
def test_patterned_scenes_agree_with_mitsuba(tracer_bin, tmp_path, scene, edit):
    """Patterns against Mitsuba's textures, within 0.1% of pixels over 2 levels: the textured mesh
    (an image by its vt, a checkered quad; 0 pixels at 640 x 480), Whitted's checkered floor (with
    opaque shadows, Mitsuba's; 2 pixels at 640 x 480), and spheres' (u, v) turned and grouped."""
    # A copy, its files (relative to the scene's folder) named by absolute paths.
    text = re.sub(r'file "([^"/][^"]*)"', lambda m: f'file "{scene.parent / m[1]}"', scene.read_text())
    path = tmp_path / scene.name
    path.write_text(text.replace(*edit))
    result = run_tool("crosscheck", path, *SMALL, "--out", tmp_path / "out", "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    assert json.loads(result.stdout)["over_2"] <= 0.001


@pytest.mark.parametrize("scene", ["gears", "mount", "teapot", "tetra"])
def test_spd_scenes_agree_at_reduced_resolution(tracer_bin, tmp_path, scene):
    """The converted SPD scenes whose pixels are well-conditioned in float32 (docs/spd.md: balls,
    rings and tree are at full size in tools/spd, with their conditioning measured)."""
    result = run_tool(
        "crosscheck",
        ROOT / "scenes" / "spd" / f"{scene}.scn",
        "--width",
        "256",
        "--out",
        tmp_path,
        "--max-over-2",
        "0.1",
        "--json",
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert json.loads(result.stdout)["over_2"] <= 0.001


def test_the_chessboard_program_agrees_at_full_resolution(tracer_bin, tmp_path):
    """scenes/chessboard.scn (loops, names, a parameter) at its own 800 x 600: balls touch their
    squares and squares their neighbours, so a few grazing pixels differ between float32 and
    double; at 300 px wide one such pixel alone pulls the PSNR under 60 dB."""
    result = run_tool("crosscheck", ROOT / "scenes" / "chessboard.scn", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["over_2"] <= 0.0001 and report["psnr"] > 60


def test_mirrored_glass_agrees_and_matches_the_unmirrored_shapes(tracer_bin, tmp_path):
    """Mirroring keeps normals outwards: the mirrored glass shapes cross-check with Mitsuba (whose
    normals the converter flips back), and tracer renders flat-shaded symmetric glass mirrored
    exactly as unmirrored."""
    result = run_tool("crosscheck", HERE / "mirrored_glass.scn", "--out", tmp_path, "--max-over-2", "0.1", "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    assert json.loads(result.stdout)["over_2"] <= 0.001
    cube = ROOT / "scenes" / "meshes" / "cube.obj"
    images = []
    for flip in (1, -1):
        scene = tmp_path / f"flip{flip}.scn"
        scene.write_text(
            "render { width 160 height 120 max_depth 6 }\ncamera { eye (0, 2, 6) lookat (0, 0.5, 0) fovy 40 }\n"
            "light { position (3, 5, 4) }\nmaterial glass { kd 0.05 kt 0.9 ior 1.5 }\n"
            "quad { corner (-4, 0, -3) edge1 (8, 0, 0) edge2 (0, 4, 0) material { ka 0.1 kd (0.8, 0.3, 0.2) } }\n"
            f"box {{ min (-0.5, 0.01, -0.5) max (0.5, 1, 0.5) transform {{ scale ({flip}, 1, 1) rotate {{ angle 30 }} "
            "translate (-1, 0, 0) } material glass }\n"
            f'mesh {{ file "{cube}" shading flat transform {{ scale (0.4, {0.4 * flip}, 0.4) rotate {{ angle 20 }} '
            "translate (1, 0.8, 0) } material glass }\n"
        )
        out = tmp_path / f"flip{flip}.exr"
        subprocess.run([tracer_bin, scene, "-o", out, "-q"], check=True)
        images.append(read_exr(out))
    assert np.array_equal(images[0], images[1])


def test_cylinders_and_discs_agree(tracer_bin, tmp_path):
    """tracer's analytic cylinders (capped, open, tilted) and disc against Mitsuba's disks and
    finely tessellated sides (xcheck.round_shapes: Mitsuba's own float32 cylinder shows shadow
    acne on 0.5% of this image's pixels)."""
    result = run_tool("crosscheck", HERE / "cylinders_discs.scn", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["over_2"] <= 0.0001 and report["psnr"] > 60
    assert (tmp_path / "cone0.obj").is_file()


def test_cones_agree_in_a_mirror(tracer_bin, tmp_path):
    """scenes/round_shapes.scn: a pointed cone with km 0.2 failed (93 pixels over 2 levels along
    its middle) while its OBJ was one ring: the normals of triangles reaching the apex,
    interpolated, bent the mirror by up to half a side's angle. Rings within 1.5 of each other's
    radius keep them true."""
    result = run_tool("crosscheck", ROOT / "scenes" / "round_shapes.scn", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["over_2"] <= 0.0001 and report["psnr"] > 70, report


def test_area_lights_agree_with_mitsuba(tracer_bin, tmp_path):
    """Two area lights (one placed by a group's rotation): Mitsuba renders each as its samples,
    point lights with their share of the colour, an independent check of where the samples lie
    and how they shade."""
    result = run_tool("crosscheck", HERE / "soft_shadows.scn", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["over_2"] <= 0.0001 and report["psnr"] > 60, report


POVRAY_MISSING = "POV-Ray is not installed (Debian's povray; tools/bootstrap --python installs it)"


@pytest.mark.skipif(shutil.which("povray") is None, reason=POVRAY_MISSING)
@pytest.mark.parametrize(
    ("scene", "most_over_2"),
    [
        (ROOT / "scenes" / "task2.scn", 0.0),
        (HERE / "glass_transparent_shadows.scn", 0.0005),
        (HERE / "cylinders_discs.scn", 0.0005),
        (ROOT / "scenes" / "whitted1980.scn", 0.0),
        (HERE / "patterns_povray.scn", 0.0005),
        (ROOT / "scenes" / "textured_vase.scn", 0.0),
        (ROOT / "scenes" / "lights" / "lamp.scn", 0.0),
        (HERE / "soft_shadows.scn", 0.0),
        (ROOT / "scenes" / "lights" / "window.scn", 0.05),
        (ROOT / "scenes" / "lights" / "stage.scn", 0.1),
        (HERE / "spot_parallel_fade.scn", 0.0),
        (HERE / "disc_light.scn", 0.0),
    ],
)
def test_povray_agrees(tracer_bin, tmp_path, scene, most_over_2):
    """POV-Ray 3.7 (xcheck.povray): task2 to the level, glass under transparent shadows (POV-Ray's
    own) and the analytic cylinders and disc within a few pixels; Whitted's checkered floor, and
    nested checkers, gradient, stripes, rings and a planar picture, within a few pixels; the
    textured mesh (POV-Ray's uv_mapping on a mesh2 given tracer's (u, v)) to the level."""
    result = run_tool("crosscheck", scene, *SMALL, "--with", "povray", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["peer"] == "povray" and report["over_2"] <= most_over_2, report
    assert report["trace_seconds"] >= 0 and (tmp_path / "scene.pov").is_file()


@pytest.mark.skipif(shutil.which("povray") is None, reason=POVRAY_MISSING)
@pytest.mark.parametrize("name", ["lens", "die", "cup", "bowl", "nesting", "carved"])
def test_povray_agrees_on_the_solids_gallery(tracer_bin, tmp_path, name):
    """The gallery of solids (docs/guide/solids.md) against POV-Ray's CSG, closed meshes with an
    inside_vector included: within the issue's 0.1% of pixels over 2 levels (at 640 x 480: 0 to
    37 pixels of 307,200)."""
    scene = ROOT / "scenes" / "solids" / f"{name}.scn"
    result = run_tool("crosscheck", scene, *SMALL, "--with", "povray", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["peer"] == "povray" and report["over_2"] <= 0.1, report


def test_a_disc_light_agrees_with_mitsuba_as_its_samples(tracer_bin, tmp_path):
    """The disc's samples (the concentric map, a second implementation in xcheck/lights.py) as
    Mitsuba's point emitters: to the level."""
    result = run_tool("crosscheck", HERE / "disc_light.scn", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["over_2"] <= 0.0001 and report["psnr"] > 60, report


def test_mitsuba_skips_spot_and_parallel_lights_saying_why(tracer_bin, tmp_path):
    """The Phong integrator has point emitters only: a spotlight, a parallel light or fading is
    skipped with the reason (exit 0), without rendering."""
    result = run_tool("crosscheck", HERE / "spot_parallel_fade.scn", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report.get("skipped") and "point emitters cannot express" in report["skipped"], report


def test_mitsuba_skips_solids_saying_why(tracer_bin, tmp_path):
    """Mitsuba 3 has no CSG: the check says so and skips the scene (exit 0), without rendering."""
    result = run_tool("crosscheck", ROOT / "scenes" / "solids" / "die.scn", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    assert "skipped" in result.stderr and "--with povray" in result.stderr
    report = json.loads(result.stdout)
    assert report["skipped"] and report["failed"] == [] and not (tmp_path / "tracer.exr").exists()


@pytest.mark.skipif(shutil.which("povray") is None, reason=POVRAY_MISSING)
def test_povray_takes_a_relative_folder_and_compares_supersampled_scenes_at_one_sample(tracer_bin, tmp_path):
    # A relative --out failed (POV-Ray ran inside it); a scene of `samples 4` was refused.
    scene = tmp_path / "four.scn"
    scene.write_text((ROOT / "scenes" / "task2.scn").read_text().replace("render {", "render { samples 4 ", 1))
    relative = os.path.relpath(tmp_path / "out", ROOT)  # run_tool runs in the checkout
    result = run_tool("crosscheck", scene, "--width", "120", "--with", "povray", "--out", relative, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    assert "comparing at 1 sample per pixel (the scene asks for 4)" in result.stderr
    assert f"the images and the report go to {relative}" in result.stderr
    assert json.loads(result.stdout)["samples"] == 1 and (tmp_path / "out" / "povray.png").is_file()


@pytest.mark.skipif(shutil.which("povray") is None, reason=POVRAY_MISSING)
def test_povray_finds_a_meshs_far_faces_past_a_near_hit(tracer_bin, tmp_path):
    """SPD gears with every gear opaque, lit directly (max_depth 0): shadow rays from a tooth's root
    meet the gear again within POV-Ray's tolerance. Unless each mesh has an inside_vector
    (xcheck.povray._mesh2), POV-Ray's search of the mesh stops there and lets the light through
    the next tooth: 20 pixels over 2 levels at 256 x 256, none with it."""
    text = (ROOT / "scenes" / "spd" / "gears.scn").read_text()
    text = text.replace("max_depth 4", "max_depth 0").replace("kt 0.8  ior 1.1", "")
    assert "max_depth 0" in text and " kt " not in text
    (tmp_path / "gears_opaque.scn").write_text(text)
    (tmp_path / "gears_meshes").symlink_to(ROOT / "scenes" / "spd" / "gears_meshes")
    result = run_tool(
        "crosscheck", tmp_path / "gears_opaque.scn", "--width", "256", "--with", "povray", "--out", tmp_path / "out",
        "--json",
    )  # fmt: skip
    assert result.returncode == 0, result.stdout + result.stderr
    assert json.loads(result.stdout)["over_2"] == 0.0


def test_transparent_shadows_are_refused_before_rendering(tracer_bin, tmp_path):
    result = run_tool("crosscheck", ROOT / "scenes" / "pencil_glass.scn", "--out", tmp_path / "out")
    assert result.returncode == 5
    assert "transparent_shadows" in result.stderr and "--with povray" in result.stderr


def test_supersampled_images_agree_too(tracer_bin, tmp_path):
    result = run_tool("crosscheck", HERE / "asymmetric.scn", "--samples", "16", "--out", tmp_path, "--json")
    assert result.returncode == 0, result.stdout + result.stderr
    assert json.loads(result.stdout)["samples"] == 16


def test_a_threshold_exceeded_exits_1(tracer_bin, tmp_path):
    # FLIP is never negative, so a negative limit must fail, through the real exit path.
    result = run_tool("crosscheck", HERE / "asymmetric.scn", "--out", tmp_path, "--max-flip", "-1")
    assert result.returncode == 1
    assert "FAIL: FLIP mean" in result.stdout
    # Each step is named as it starts and timed as it ends (the renders can take minutes).
    for step in ("rendering with Mitsuba 3 (", "rendering with tracer", "comparing (FLIP)"):
        assert f"crosscheck: {step}" in result.stderr, result.stderr
    assert result.stderr.count(": done in ") == 3, result.stderr


def test_a_long_step_says_it_is_still_running(capsys):
    import time

    from tracer_tools.xcheck import progress

    with progress.step("crosscheck", "rendering with Mitsuba 3", heartbeat=0.05):
        time.sleep(0.18)
    lines = capsys.readouterr().err.splitlines()
    assert lines[0] == "crosscheck: rendering with Mitsuba 3..."
    assert 2 <= sum(line.startswith("crosscheck: still rendering with Mitsuba 3 (") for line in lines) <= 4
    assert lines[-1].startswith("crosscheck: rendering with Mitsuba 3: done in 0.")


def test_an_invalid_scene_exits_3_with_tracers_diagnostic(tracer_bin, tmp_path):
    bad = tmp_path / "bad.scn"
    bad.write_text("sphere { center (0, 0, 0)  radius -1 }\n")
    result = run_tool("crosscheck", bad, "--out", tmp_path / "out")
    assert result.returncode == 3
    assert "bad.scn:1:" in result.stderr and "error:" in result.stderr
    assert "crosscheck: error: tracer could not load" in result.stderr
    assert not (tmp_path / "out").exists()


def test_missing_mitsuba_exits_4_with_a_clear_message(tracer_bin, tmp_path):
    hidden = tmp_path / "hide"
    (hidden / "mitsuba").mkdir(parents=True)
    (hidden / "mitsuba" / "__init__.py").write_text("raise ImportError(\"No module named 'mitsuba'\")\n")
    result = run_tool("crosscheck", HERE / "asymmetric.scn", "--out", tmp_path / "out", env={"PYTHONPATH": str(hidden)})
    assert result.returncode == 4
    assert "Mitsuba 3 is not usable" in result.stderr and "tools/bootstrap --python" in result.stderr


def test_mitsuba_render_writes_the_image_and_its_xml(tracer_bin, tmp_path):
    result = run_tool("render", HERE / "asymmetric.scn", "-o", tmp_path / "m.png")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "m.png").is_file() and (tmp_path / "m.png.xml").is_file()


def test_metrics_of_identical_images():
    image = np.random.default_rng(1).random((20, 30, 3)).astype(np.float32)
    result = metrics.compare(image, image)
    assert result.rmse == 0 and result.psnr == float("inf") and result.flip_mean == 0
    assert result.over_1 == result.over_2 == result.over_8 == 0 and result.max_levels == 0


def test_metrics_count_levels_per_pixel():
    reference = np.full((10, 10, 3), 100 / 255, dtype=np.float32)
    test = reference.copy()
    test[0, 0, 1] += 3 / 255  # one pixel 3 levels off (in green only)
    test[5, 5] += 9 / 255  # one pixel 9 levels off
    test[9, 9, 2] += 2 / 255  # one pixel 2 levels off: not over 2
    result = metrics.compare(reference, test)
    assert (result.over_1, result.over_2, result.over_8) == (0.03, 0.02, 0.01)
    assert result.max_levels == 9
    assert result.rmse == pytest.approx(np.sqrt((9 + 3 * 81 + 4) / 300) / 255, rel=1e-4)
    assert result.flip_mean > 0
    heat = metrics.heat_map(reference, test)
    assert tuple(heat[5, 5]) == metrics.HEAT_BINS[2][1] and tuple(heat[0, 0]) == metrics.HEAT_BINS[1][1]
    assert tuple(heat[9, 9]) == metrics.HEAT_BINS[0][1] and tuple(heat[3, 3]) == (25, 25, 25)


def test_a_real_difference_is_caught(dump, tmp_path):
    # The same scene with the light moved a little: the check must see it.
    from tracer_tools.xcheck import mitsuba_render

    scene = dump(HERE / "asymmetric.scn")
    moved = json.loads(json.dumps(scene))
    moved["lights"][0]["position"][0] += 0.2
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    a = mitsuba_render.render_scene(scene, tmp_path / "a")
    b = mitsuba_render.render_scene(moved, tmp_path / "b")
    assert metrics.compare(a, b).over_2 > 0.01


def test_a_scene_mitsuba_cannot_take_exits_5_before_rendering(tracer_bin, tmp_path):
    deep = tmp_path / "deep.scn"
    deep.write_text(
        "render { max_depth 65 }\ncamera { eye (0, 0, 5)  lookat (0, 0, 0) }\n"
        "sphere { center (0, 0, 0)  radius 1  material { kd 1 } }\nlight { position (1, 1, 3) }\n"
    )
    result = run_tool("crosscheck", deep, "--out", tmp_path / "out")
    assert result.returncode == 5
    assert "max_depth 65" in result.stderr and "at most 64" in result.stderr
    assert not (tmp_path / "out" / "tracer.exr").exists()


@pytest.mark.parametrize("extra", [["--width", "120"], ["--width", "90", "--samples", "4", "--max-depth", "2"]])
def test_in_process_pixels_equal_the_executables_exr(tracer_bin, tmp_path, extra):
    from tracer_tools import package
    from tracer_tools.xcheck import tracer_cli

    if package.imported_beside(tracer_bin) is None:
        pytest.skip(f"no tracer package built beside {tracer_bin} (tools/bootstrap --python builds it)")
    scene = ROOT / "scenes" / "task2.scn"
    pixels, stats = tracer_cli.render_pixels(scene, extra)
    tracer_cli.render(scene, tmp_path / "cli.exr", extra)
    assert pixels.dtype == np.float32 and np.array_equal(pixels, read_exr(tmp_path / "cli.exr"))
    assert stats["rays"]["primary"] == pixels.shape[0] * pixels.shape[1] * stats["samples"]


def test_options_the_package_lacks_leave_the_render_to_the_executable():
    from tracer_tools.xcheck import tracer_cli

    assert tracer_cli.package_call(["--samples", "4", "-D", "r=0.5", "--threads", "2"]) == (
        {"samples": "4"},
        {"r": "0.5"},
        2,
    )
    assert tracer_cli.package_call(["--encoding", "srgb"]) is None
    assert tracer_cli.package_call(["--width"]) is None
