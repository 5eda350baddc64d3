"""The farm's parts on their own: tiles cover the frame once, PPM tiles are read exactly, and a bad
jobs file or option is refused with a message before any work."""

import json
import os

import numpy as np
import pytest
from conftest import ROOT, SCENES, farm

from tracer_tools.farm import resume
from tracer_tools.farm.images import decode_ppm
from tracer_tools.farm.jobs import Job, JobError, check_job, jobs_from_file
from tracer_tools.farm.tiles import Canvas, Region, split, tile_size_for


@pytest.mark.parametrize("width,height,tile", [(1, 1, 1), (1200, 800, 347), (641, 479, 64), (5, 300, 7), (64, 64, 64)])
def test_tiles_cover_every_pixel_exactly_once(width, height, tile):
    counts = np.zeros((height, width), dtype=int)
    for region in split(width, height, tile):
        assert 1 <= region.width <= tile and 1 <= region.height <= tile
        counts[region.y0 : region.y0 + region.height, region.x0 : region.x0 + region.width] += 1
    assert (counts == 1).all()


def test_default_tile_size_gives_about_16_tiles_per_worker_and_at_least_32_pixels():
    assert len(split(1200, 800, tile_size_for(1200, 800, 2))) in range(28, 45)
    assert tile_size_for(100, 100, 64) == 32


def test_canvas_knows_when_complete_and_refuses_a_tile_of_the_wrong_size():
    canvas = Canvas(4, 2, np.uint8, 2)
    canvas.paste(Region(0, 0, 2, 2), np.full((2, 2, 3), 7, np.uint8))
    assert not canvas.complete()
    with pytest.raises(ValueError, match="came back as 3 x 2"):
        canvas.paste(Region(2, 0, 2, 2), np.zeros((2, 3, 3), np.uint8))
    canvas.paste(Region(2, 0, 2, 2), np.full((2, 2, 3), 9, np.uint8))
    assert canvas.complete() and canvas.pixels[1, 3, 2] == 9 and canvas.pixels[0, 0, 0] == 7


def test_ppm_tiles_are_read_exactly_even_when_the_pixels_start_with_whitespace_bytes():
    pixels = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    pixels[0, 0] = [10, 32, 9]  # newline, space and tab bytes right after the header
    data = b"P6\n3 2\n255\n" + pixels.tobytes()
    assert np.array_equal(decode_ppm(data), pixels)
    with pytest.raises(ValueError):
        decode_ppm(b"P5\n3 2\n255\n" + bytes(6))
    with pytest.raises(ValueError, match="only"):
        decode_ppm(b"P6\n3 2\n255\n" + bytes(5))


@pytest.mark.parametrize(
    "content,message",
    [
        ("not json", "not a JSON list of jobs"),
        ("[]", "non-empty JSON list"),
        ('[{"scene": "a.scn"}]', 'needs "scene" and "output"'),
        ('[{"scene": "a.scn", "output": "a.png", "sample": 4}]', "unknown key(s) sample"),
        ('[{"scene": "a.scn", "output": "a.png", "define": [1]}]', '"define" is an object'),
        ('[{"scene": "a.scn", "output": "a.png"}, {"scene": "b.scn", "output": "a.png"}]', "two jobs write"),
    ],
)
def test_bad_jobs_files_are_refused(tmp_path, content, message):
    path = tmp_path / "jobs.json"
    path.write_text(content)
    with pytest.raises(JobError, match=message.replace("(", r"\(").replace(")", r"\)")):
        jobs_from_file(str(path))


def test_hostile_jobs_files_are_refused_with_a_message(tmp_path):
    # A path with a NUL byte gave a traceback; a FIFO as the jobs file blocked for ever.
    path = tmp_path / "jobs.json"
    path.write_text('[{"scene": "a\\u0000.scn", "output": "a.png"}]')
    with pytest.raises(JobError, match="NUL byte"):
        jobs_from_file(str(path))
    fifo = tmp_path / "fifo.json"
    os.mkfifo(fifo)
    with pytest.raises(JobError, match="not a regular file"):
        jobs_from_file(str(fifo))


def test_a_hundred_thousand_jobs_are_read_and_checked_for_clashes_in_linear_time(tmp_path):
    # The duplicate-output check was quadratic (4x10^4 jobs: 15 s); 10^5 now read in well under
    # a second, and a clash between the first and the last is still found.
    jobs = [{"scene": "s.scn", "output": f"out{i}.png", "define": {"i": i}} for i in range(100_000)]
    path = tmp_path / "jobs.json"
    path.write_text(json.dumps(jobs))
    assert len(jobs_from_file(str(path))) == 100_000
    jobs[-1]["output"] = "out0.png"
    path.write_text(json.dumps(jobs))
    with pytest.raises(JobError, match="two jobs write"):
        jobs_from_file(str(path))


def test_jobs_file_paths_are_relative_to_the_file(tmp_path):
    (tmp_path / "sub").mkdir()
    path = tmp_path / "sub" / "jobs.json"
    path.write_text(json.dumps([{"scene": "../a.scn", "output": "out.png", "samples": 4, "define": {"r": 0.5}}]))
    (job,) = jobs_from_file(str(path))
    assert job.scene == str(tmp_path / "sub" / "../a.scn") and job.output == str(tmp_path / "sub" / "out.png")
    assert job.tracer_arguments()[1:] == ["-D", "r=0.5", "--samples", "4"]


@pytest.mark.parametrize(
    "arguments,code,message",
    [
        (["-o", "out.png"], 2, "give one scene"),
        ([str(SCENES / "task2.scn")], 2, "no output image"),
        ([str(SCENES / "task2.scn"), "-o", "out.png", "--workers", "0"], 2, "--workers"),
        ([str(SCENES / "task2.scn"), "-o", "/no/such/folder/out.png"], 3, "no such folder"),
        ([str(SCENES / "task2.scn"), "-o", "out.unknown"], 3, "unknown image format"),
        ([str(SCENES / "task2.scn"), "-o", "out.png", "-D", "novalue"], 2, "expected NAME=VALUE"),
        (
            [str(SCENES / "task2.scn"), "-o", "out.png", "--address", "tcp://127.0.0.1:9", "--connect-timeout", "1"],
            3,
            "cannot reach the Dask scheduler at 'tcp://127.0.0.1:9'",
        ),
    ],
)
def test_bad_command_lines_are_refused_before_any_tile(tracer_bin, tmp_path, arguments, code, message):
    result = farm(*arguments, tracer=tracer_bin, cwd=tmp_path)
    assert result.returncode == code, result.stderr
    assert message in result.stderr
    assert "tile" not in result.stderr.replace("--tile", "") and "Traceback" not in result.stderr
    assert not (tmp_path / "out.png").exists()


def test_images_are_written_whole_or_not_at_all(tmp_path):
    from conftest import read_pixels

    from tracer_tools.farm.images import write_atomically

    pixels = np.arange(4 * 5 * 3, dtype=np.uint8).reshape(4, 5, 3)
    (tmp_path / "out.png").write_bytes(b"the old file")
    write_atomically(str(tmp_path / "out.png"), pixels)
    assert np.array_equal(read_pixels(tmp_path / "out.png")[0], pixels)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.png"]  # no temporary file left
    with pytest.raises(OSError):
        write_atomically(str(tmp_path / "missing" / "out.png"), pixels)


def checked_job(tracer_bin, tmp_path):
    """A job whose scene includes a file and reads a mesh, checked by tracer (inputs and frame set)."""
    (tmp_path / "part.scn").write_text("sphere { center (0, 0, 0) radius 1 material { kd 1 } }\n")
    (tmp_path / "cube.obj").write_bytes((ROOT / "scenes" / "meshes" / "cube.obj").read_bytes())
    (tmp_path / "s.scn").write_text(
        'camera { eye (0, 0, 7) lookat (0, 0, 0) }\ninclude "part.scn"\nlight { position (0, 3, 3) }\n'
        'mesh { file "cube.obj" material { kd 1 } }\nrender { width 64 height 48 }\n'
    )
    job = Job(str(tmp_path / "s.scn"), str(tmp_path / "out.png"))
    check_job(str(tracer_bin), job)
    return job


def test_a_job_s_identity_covers_tracer_and_every_file_the_scene_reads(tracer_bin, tmp_path):
    job = checked_job(tracer_bin, tmp_path)
    assert sorted(os.path.basename(path) for path in job.inputs) == ["cube.obj", "part.scn"]
    first = resume.identity(str(tracer_bin), job)
    assert first == resume.identity(str(tracer_bin), job)
    for name in ("part.scn", "cube.obj", "s.scn"):
        with open(tmp_path / name, "a") as file:
            file.write("\n# changed\n")
        changed = resume.identity(str(tracer_bin), job)
        assert changed != first, name
        first = changed
    job.overrides["samples"] = "4"
    assert resume.identity(str(tracer_bin), job) != first


def test_kept_tiles_are_reused_only_by_the_same_job_and_tile_size(tracer_bin, tmp_path):
    job = checked_job(tracer_bin, tmp_path)
    manifest = resume.identity(str(tracer_bin), job)
    store = resume.TileStore(job.output, dict(manifest))
    assert store.resume(None, 32) == (32, {})
    tile = np.full((32, 32, 3), 7, np.uint8)
    store.keep(Region(0, 0, 32, 32), tile)
    store.keep(Region(32, 0, 32, 32), np.zeros((16, 16, 3), np.uint8))  # the wrong size: not reused
    (tmp_path / ".out.png.farm" / "tile-0-32-32-16.npy").write_bytes(b"not a tile")
    (tmp_path / ".out.png.farm" / "notes.txt").write_text("a stranger's file")

    # The same job, even with another default tile size: the kept size and the good tile.
    tile_size, kept = resume.TileStore(job.output, dict(manifest)).resume(None, 16)
    assert tile_size == 32 and list(kept) == [Region(0, 0, 32, 32)] and np.array_equal(kept[Region(0, 0, 32, 32)], tile)
    # Another tile size asked for, or another job: the folder starts over.
    assert resume.TileStore(job.output, dict(manifest)).resume(16, 32) == (16, {})
    assert not (tmp_path / ".out.png.farm").exists()
    resume.TileStore(job.output, dict(manifest)).keep(Region(0, 0, 32, 32), tile)
    assert resume.TileStore(job.output, {**manifest, "arguments": ["other"]}).resume(None, 32) == (32, {})
    assert not (tmp_path / ".out.png.farm").exists()


def kept_store(tracer_bin, tmp_path):
    """A job with one good tile kept (region 0 0 32 32) and its manifest."""
    job = checked_job(tracer_bin, tmp_path)
    manifest = resume.identity(str(tracer_bin), job)
    store = resume.TileStore(job.output, dict(manifest))
    store.resume(None, 32)
    store.keep(Region(0, 0, 32, 32), np.full((32, 32, 3), 7, np.uint8))
    return job, manifest, tmp_path / ".out.png.farm"


@pytest.mark.parametrize(
    "change,reason",
    [
        ({"tile": 0}, "tile size 0 is not a whole number"),
        ({"tile": True}, "tile size True is not a whole number"),
        ({"tile": 1}, "would make over 64 times the tiles"),
        ({"tile": "32"}, "tile size 32 is not a whole number"),
        ({"extra": 1}, "does not have the expected fields"),
    ],
)
def test_a_tampered_manifest_is_discarded_with_one_line(tracer_bin, tmp_path, capsys, change, reason):
    job, manifest, folder = kept_store(tracer_bin, tmp_path)
    earlier = json.loads((folder / "manifest.json").read_text())
    (folder / "manifest.json").write_text(json.dumps({**earlier, **change}))
    assert resume.TileStore(job.output, dict(manifest)).resume(None, 32) == (32, {})
    assert reason in capsys.readouterr().err
    assert not folder.exists()


def test_a_manifest_with_true_for_one_is_another_job(tracer_bin, tmp_path):
    job, manifest, folder = kept_store(tracer_bin, tmp_path)
    earlier = json.loads((folder / "manifest.json").read_text())
    (folder / "manifest.json").write_text(json.dumps({**earlier, "float": 0 if not earlier["float"] else 1}))
    assert resume.TileStore(job.output, dict(manifest)).resume(None, 32) == (32, {})


@pytest.mark.parametrize("kind", ["fifo", "device", "huge"])
def test_a_manifest_that_is_no_regular_file_is_never_read(tracer_bin, tmp_path, capsys, kind):
    job, manifest, folder = kept_store(tracer_bin, tmp_path)
    (folder / "manifest.json").unlink()
    if kind == "fifo":
        os.mkfifo(folder / "manifest.json")
    elif kind == "device":
        os.symlink("/dev/zero", folder / "manifest.json")
    else:
        with open(folder / "manifest.json", "wb") as file:
            file.truncate(2 << 20)
    assert resume.TileStore(job.output, dict(manifest)).resume(None, 32) == (32, {})
    assert "the kept tiles of" in capsys.readouterr().err


def test_tiles_are_trusted_only_with_their_digest_and_size(tracer_bin, tmp_path, capsys):
    job, manifest, folder = kept_store(tracer_bin, tmp_path)
    (good,) = [name for name in os.listdir(folder) if name.startswith("tile-")]
    region, digest = resume.region_of(good)
    # A planted tile of the right shape under a made-up digest, and one claiming 10^6 x 10^6 pixels.
    planted = np.zeros((32, 16, 3), np.uint8)
    np.save(folder / f"tile-32-0-32-16-{'0' * 32}.npy", planted)
    with open(folder / f"tile-0-32-32-16-{'1' * 32}.npy", "wb") as file:
        np.lib.format.write_array_header_1_0(file, {"descr": "|u1", "fortran_order": False, "shape": (10**6, 10**6, 3)})
    os.mkfifo(folder / f"tile-32-32-32-16-{'2' * 32}.npy")
    tile, kept = resume.TileStore(job.output, dict(manifest)).resume(None, 32)
    assert tile == 32 and list(kept) == [region]
    assert "3 kept tiles of" in capsys.readouterr().err
    # The good tile copied to another job's folder does not pass there.
    other = resume.TileStore(job.output, {**manifest, "arguments": [*manifest["arguments"], "-D", "x=1"]})
    other.manifest["tile"] = 32
    assert other._load(good, region, digest) is None


def test_the_folder_of_kept_tiles_is_never_a_link_or_a_file(tracer_bin, tmp_path, capsys):
    job = checked_job(tracer_bin, tmp_path)
    manifest = resume.identity(str(tracer_bin), job)
    target = tmp_path / "elsewhere"
    target.mkdir()
    (target / "precious").write_text("x")
    os.symlink(target, tmp_path / ".out.png.farm")
    assert resume.TileStore(job.output, dict(manifest)).resume(None, 32) == (32, {})
    assert (target / "precious").exists() and not os.path.lexists(tmp_path / ".out.png.farm")
    assert "symbolic link" in capsys.readouterr().err
    (tmp_path / ".out.png.farm").write_text("a user's file")
    with pytest.raises(JobError, match="is not the farm's folder of kept tiles"):
        resume.TileStore(job.output, dict(manifest)).resume(None, 32)


def test_tracer_is_hashed_once_for_many_jobs(tracer_bin, tmp_path):
    job = checked_job(tracer_bin, tmp_path)
    resume._digest_of.cache_clear()
    for _ in range(1000):
        resume.identity(str(tracer_bin), job)
    assert resume._digest_of.cache_info().misses == 1 + 1 + len(job.inputs)  # tracer, the scene, its inputs
