"""The tracer Python package (src/python/tracer): arrays equal to the command line's EXR output
bit for bit, errors as data, parameters and includes, the GIL released, Ctrl-C, memory, hostile
input. Run by ctest (`python`) with the package built into build/release/python."""

import json
import os
import pathlib
import signal
import subprocess
import threading
import time

import numpy
import OpenImageIO as oiio
import pytest
import tracer

ROOT = pathlib.Path(__file__).resolve().parents[2]
TRACER = os.environ.get("TRACER_BIN", str(ROOT / "build" / "release" / "tracer"))
SMALL = """camera { eye (0, 0, 7) lookat (0, 0, 0) up (0, 1, 0) fovy 45 }
render { width 40 height 30 }
light { position (5, 5, 5) }
sphere { center (0, 0, 0) radius 1 material { kd (0.8, 0.3, 0.2) ks 0.5 n 40 km 0.2 } }
plane { point (0, -1, 0) normal (0, 1, 0) material { kd 0.6 km 0.3 } }
"""


def command_line_exr(tmp_path, scene, *options):
    out = tmp_path / "cli.exr"
    subprocess.run([TRACER, str(scene), "-o", str(out), "--quiet", *options], check=True, cwd=ROOT)
    image = oiio.ImageInput.open(str(out))
    pixels = image.read_image(format=oiio.FLOAT)
    image.close()
    return pixels


@pytest.mark.parametrize(
    "scene, settings, options",
    [
        ("scenes/task2.scn", {}, []),
        ("scenes/bunny_room.scn", {"width": 240}, ["--width", "240"]),
        ("scenes/glass.scn", {"width": 200, "samples": 4}, ["--width", "200", "--samples", "4"]),
        ("scenes/task2.scn", {"region": (100, 50, 64, 48)}, ["--region", "100", "50", "64", "48"]),
    ],
)
def test_array_equals_the_command_lines_exr_bit_for_bit(tmp_path, scene, settings, options):
    pixels = tracer.load(ROOT / scene).render(**settings)
    expected = command_line_exr(tmp_path, scene, *options)
    assert pixels.dtype == numpy.float32 and pixels.flags.c_contiguous and pixels.flags.owndata is False
    assert pixels.shape == expected.shape
    assert numpy.array_equal(pixels.view(numpy.uint32), expected.view(numpy.uint32))


@pytest.mark.parametrize(
    "scene, settings, options",
    [
        ("scenes/bunny_room.scn", {"width": 600, "encoding": "linear"}, ["--width", "600"]),
        ("scenes/task2.scn", {"region": (100, 50, 64, 48), "encoding": "srgb"}, ["--region", "100", "50", "64", "48"]),
    ],
)
def test_eight_bit_pixels_equal_the_command_lines_png(tmp_path, scene, settings, options):
    pixels = tracer.load(ROOT / scene).render(**settings)
    out = tmp_path / "cli.png"
    encoding = ["--encoding", settings["encoding"]]
    subprocess.run([TRACER, scene, "-o", str(out), "--quiet", *encoding, *options], check=True, cwd=ROOT)
    image = oiio.ImageInput.open(str(out))
    expected = image.read_image(format=oiio.UINT8)
    image.close()
    assert pixels.dtype == numpy.uint8 and pixels.shape == expected.shape
    assert numpy.array_equal(pixels, expected)
    with pytest.raises(ValueError, match="encoding"):
        tracer.load(ROOT / scene).render(width=8, encoding="gamma")


def test_the_world_is_built_once_and_again_when_its_settings_change():
    scene = tracer.load(ROOT / "scenes/bunny_room.scn")

    def mesh_stats(**settings):
        return scene.render(width=40, threads=1, return_stats=True, **settings)[1]["meshes"][0]

    first = mesh_stats()
    assert mesh_stats(samples=4) == first  # the same world: its build's own figures, time and all
    other = mesh_stats(leaf_size=1)
    assert other["leaf_size_max"] == 1 and first["leaf_size_max"] > 1
    assert mesh_stats(leaf_size=1, samples=4) == other
    assert mesh_stats()["leaf_size_max"] == first["leaf_size_max"]  # rebuilt with the scene's own


def test_settings_that_come_and_go_between_renders_apply_to_each_alone():
    # The scene with a render's settings is kept for the next render with the same ones: a
    # render with other settings, or with none, must not see the last one's.
    scene = tracer.loads(SMALL)
    plain = scene.render(threads=1)
    wide, _ = scene.render(width=80, samples=4, threads=1), scene.render(width=20, threads=1)
    assert numpy.array_equal(scene.render(threads=1), plain) and plain.shape == (30, 40, 3)
    assert numpy.array_equal(scene.render(width=80, samples=4, threads=1), wide) and wide.shape == (60, 80, 3)
    with pytest.raises(ValueError):
        scene.render(width=0)
    assert numpy.array_equal(scene.render(threads=1), plain)


def test_a_stop_function_stops_a_render_and_the_scene_stays_usable():
    scene = tracer.load(ROOT / "scenes/task2.scn")
    stop = threading.Event()
    timer = threading.Timer(0.3, stop.set)
    timer.start()
    with pytest.raises(tracer.RenderStopped):
        scene.render(width=8192, samples=64, threads=1, stop=stop.is_set)  # hours if not stopped
    timer.join()

    def refuses():
        raise LookupError("stop's own error")

    with pytest.raises(LookupError, match="stop's own error"):
        scene.render(width=8192, samples=64, threads=1, stop=refuses)
    with pytest.raises(TypeError, match="stop"):
        scene.render(width=8, stop=True)
    calls = []
    pixels = scene.render(width=60, stop=lambda: calls.append(1) and False)
    assert pixels.shape == (40, 60, 3)


def test_two_threads_render_one_scene_at_once():
    scene = tracer.load(ROOT / "scenes/bunny_room.scn")
    together = [None, None]

    def run(i):
        together[i] = scene.render(width=160, threads=1, region=(0, 40 * i, 160, 40))

    workers = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for worker in workers:
        worker.start()
    for worker in workers:
        worker.join()
    assert numpy.array_equal(numpy.concatenate(together), scene.render(width=160, region=(0, 0, 160, 80)))


def test_description_is_dump_json():
    expected = json.loads(
        subprocess.run(
            [TRACER, "scenes/task2.scn", "--dump-json"], cwd=ROOT, check=True, capture_output=True, text=True
        ).stdout
    )
    assert tracer.load(ROOT / "scenes/task2.scn").description == expected


def test_stats_are_the_command_lines_figures():
    pixels, stats = tracer.loads(SMALL).render(return_stats=True)
    assert pixels.shape == (30, 40, 3)
    assert stats["rays"]["primary"] == 40 * 30


@pytest.mark.parametrize("case", ["repeated_errors", "unknown_key", "adaptive_bad"])
def test_errors_as_data_print_as_the_command_line(monkeypatch, case):
    folder = ROOT / "tests" / "diagnostics"
    if not (folder / f"{case}.scn").exists():
        pytest.skip(f"no golden case {case}")
    expected = (folder / f"{case}.expected").read_text().split("\n", 1)[1]
    monkeypatch.chdir(folder)
    with pytest.raises(tracer.SceneError) as raised:
        tracer.load(f"{case}.scn")
    error = raised.value
    assert error.text == expected
    assert str(error) == expected.rstrip("\n")
    first = error.errors[0]
    assert first.path.endswith(".scn") and first.line > 0 and first.column > 0 and first.message
    assert first.text.startswith(f"{first.path}:{first.line}:{first.column}: error: {first.message}")


def test_parameters_and_includes(tmp_path):
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "ball.scn").write_text("sphere { center (0, 0, 0) radius r material { kd 1 } }\n")
    text = SMALL.replace("sphere {", 'param r = 1\ninclude "ball.scn"\nsphere {', 1)
    scene = tracer.loads(text, name=str(tmp_path / "t.scn"), defines={"r": 0.25}, include=[tmp_path / "lib"])
    radii = sorted(s["radius"] for s in scene.description["spheres"])
    assert radii == [0.25, 1]
    with pytest.raises(tracer.SceneError, match="ball.scn"):
        tracer.loads(text, name=str(tmp_path / "t.scn"))


def test_the_gil_is_released_during_a_render():
    scene = tracer.load(ROOT / "scenes/task2.scn")
    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    scene.render(threads=1)
    done.set()
    counter.join()
    assert ticks > 5  # the counting thread ran while the render held no GIL


def test_two_threads_render_two_scenes():
    scenes = [tracer.load(ROOT / "scenes/task2.scn"), tracer.loads(SMALL)]
    alone = [scene.render(width=120, threads=1) for scene in scenes]
    together = [None, None]

    def run(i):
        together[i] = scenes[i].render(width=120, threads=1)

    workers = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for worker in workers:
        worker.start()
    for worker in workers:
        worker.join()
    for a, b in zip(alone, together, strict=True):
        assert numpy.array_equal(a, b)


def test_ctrl_c_stops_a_long_render_and_the_module_stays_usable():
    scene = tracer.load(ROOT / "scenes/task2.scn")
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.render(width=8192, samples=64, threads=1)  # hours if not stopped
    timer.join()
    assert scene.render(width=60).shape == (40, 60, 3)


def test_memory_is_freed_across_cycles():
    def rss_kib():
        return int(pathlib.Path("/proc/self/statm").read_text().split()[1]) * os.sysconf("SC_PAGE_SIZE") // 1024

    def cycles(n):
        for _ in range(n):
            tracer.loads(SMALL).render(width=32, threads=1)

    cycles(100)
    before = rss_kib()
    cycles(1000)
    assert rss_kib() - before < 16 * 1024  # a leak of one 32 x 24 image per cycle alone would be 9 MiB


def test_write_image_writes_as_the_command_line(tmp_path):
    scene = tracer.load(ROOT / "scenes/task2.scn")
    pixels = scene.render(width=300)
    tracer.write_image(tmp_path / "py.exr", pixels)
    written = oiio.ImageInput.open(str(tmp_path / "py.exr"))
    assert numpy.array_equal(written.read_image(format=oiio.FLOAT), pixels)
    written.close()
    tracer.write_image(tmp_path / "py.png", pixels, encoding="srgb")
    assert (tmp_path / "py.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(OSError, match="no-such-folder"):
        tracer.write_image(tmp_path / "no-such-folder" / "x.png", pixels)
    with pytest.raises(ValueError, match="encoding"):
        tracer.write_image(tmp_path / "x.png", pixels, encoding="gamma")
    assert tracer.Picture(pixels)._repr_png_()[:4] == b"\x89PNG"


def test_hostile_inputs_raise_clear_errors():
    with pytest.raises(tracer.SceneError):
        tracer.loads("camera { eye (0, 0, 7)\x00 lookat (0, 0, 0) }")
    with pytest.raises(tracer.SceneError):
        tracer.loads("#" * 100_000_000)  # 10^8 characters: refused or read, never a crash
    scene = tracer.loads(SMALL)
    for width in (0, 10**9, -1):
        with pytest.raises(ValueError, match="width"):
            scene.render(width=width)
    with pytest.raises(ValueError):
        scene.render(region=(0, 0, 500, 500))
    with pytest.raises(ValueError, match="unknown|accel"):
        scene.render(accel="quantum")
    with pytest.raises(TypeError):
        scene.render(width="wide" * 3, threads="all")
    assert scene.render().shape == (30, 40, 3)  # the scene still works after every refusal
    with pytest.raises(tracer.SceneError) as raised:
        tracer.load("/no/such/scene.scn")
    assert raised.value.unreadable


def test_import_leaves_numpy_alone():
    code = "import sys, tracer; print('numpy' in sys.modules)"
    env = dict(os.environ)
    out = subprocess.run([os.sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    assert out.stdout.strip() == "False"


def test_the_committed_stub_is_the_extensions(tmp_path):
    out = tmp_path / "_tracer.pyi"
    subprocess.run(
        [os.sys.executable, "-m", "nanobind.stubgen", "-q", "-m", "tracer._tracer", "-o", str(out)],
        check=True,
        capture_output=True,
    )
    committed = ROOT / "src" / "python" / "tracer" / "_tracer.pyi"
    assert out.read_text() == committed.read_text(), "regenerate it: python -m nanobind.stubgen -m tracer._tracer"
