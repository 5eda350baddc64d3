"""tracer --region and --region-list: each pixel of a window as the full render has it."""

import random
import subprocess

import numpy as np
import pytest
from conftest import SCENES, read_pixels, render

# Scenes and sizes kept small: the full render is the reference of every window.
CASES = [("task2", ["--width", "300"]), ("bunny_room", ["--width", "240"]), ("many_spheres", ["--width", "200"])]


@pytest.mark.parametrize("samples", [1, 16])
@pytest.mark.parametrize("scene,size", CASES)
def test_random_windows_equal_the_full_render(tracer_bin, tmp_path, scene, size, samples):
    settings = [*size, "--samples", samples]
    full_png = render(tracer_bin, SCENES / f"{scene}.scn", tmp_path / "full.png", *settings)
    full_exr = render(tracer_bin, SCENES / f"{scene}.scn", tmp_path / "full.exr", *settings)
    height, width = full_png.shape[:2]
    generator = random.Random(f"{scene}-{samples}")
    for trial in range(4):
        w, h = generator.randint(1, width), generator.randint(1, height)
        x0, y0 = generator.randint(0, width - w), generator.randint(0, height - h)
        region = ["--region", x0, y0, w, h]
        piece = render(tracer_bin, SCENES / f"{scene}.scn", tmp_path / f"piece{trial}.png", *settings, *region)
        assert piece.shape == (h, w, 3)
        assert np.array_equal(piece, full_png[y0 : y0 + h, x0 : x0 + w])
        piece = render(tracer_bin, SCENES / f"{scene}.scn", tmp_path / f"piece{trial}.exr", *settings, *region)
        assert np.array_equal(piece, full_exr[y0 : y0 + h, x0 : x0 + w])


def test_exr_records_the_window_inside_the_frame(tracer_bin, tmp_path):
    render(tracer_bin, SCENES / "task2.scn", tmp_path / "piece.exr", "--region", 100, 50, 300, 200)
    _, spec = read_pixels(tmp_path / "piece.exr")
    assert (spec.x, spec.y, spec.width, spec.height) == (100, 50, 300, 200)  # the data window
    assert (spec.full_x, spec.full_y, spec.full_width, spec.full_height) == (0, 0, 1200, 800)  # the display window
    render(tracer_bin, SCENES / "task2.scn", tmp_path / "piece.png", "--region", 100, 50, 300, 200)
    _, spec = read_pixels(tmp_path / "piece.png")
    assert (spec.width, spec.height, spec.full_width, spec.full_height) == (300, 200, 300, 200)


@pytest.mark.parametrize(
    "region,message",
    [
        ([0, 0, 0, 10], "is empty"),
        ([0, 0, 10, 0], "is empty"),
        ([-1, 0, 10, 10], "starts outside the image"),
        ([1195, 0, 10, 10], "right edge"),
        ([0, 795, 10, 10], "bottom edge"),
        ([1200, 800, 1, 1], "right edge"),
    ],
)
def test_bad_regions_are_errors_and_write_nothing(tracer_bin, tmp_path, region, message):
    output = tmp_path / "piece.png"
    result = subprocess.run(
        [tracer_bin, SCENES / "task2.scn", "-o", output, "--region", *map(str, region)], capture_output=True, text=True
    )
    assert result.returncode == 2
    assert message in result.stderr and "(the image is 1200 x 800)" in result.stderr
    assert not output.exists()


def test_region_list_renders_each_line_and_answers_it(tracer_bin, tmp_path):
    full = render(tracer_bin, SCENES / "task2.scn", tmp_path / "full.png", "--width", "300")
    lines = [
        f"0 0 100 50 {tmp_path / 'a.png'}",
        f"250 150 60 10 {tmp_path / 'b.png'}",
        "not a region",
        "9" * 100000,
        f"10 20 30 40 {tmp_path / 'c.exr'}",
    ]
    result = subprocess.run(
        [tracer_bin, SCENES / "task2.scn", "--width", "300", "--region-list"],
        input="\n".join(lines),  # the last line without its newline
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stderr
    replies = result.stdout.splitlines()
    assert replies[0] == f"done {tmp_path / 'a.png'}"
    assert replies[1].startswith(f"error {tmp_path / 'b.png'}: region 250 150 60 10 reaches past the image's right")
    assert replies[2].startswith("error: expected 'X0 Y0 W H OUTPUT'")
    assert replies[3] == "error: a request line longer than 16384 characters"  # read in bounded memory
    assert replies[4] == f"done {tmp_path / 'c.exr'}"
    assert np.array_equal(read_pixels(tmp_path / "a.png")[0], full[0:50, 0:100])
    assert not (tmp_path / "b.png").exists()
    assert read_pixels(tmp_path / "c.exr")[1].x == 10
