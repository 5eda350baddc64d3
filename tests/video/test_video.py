"""tools/video: tracer's numbered frames into .mp4 and .webm through PyAV, decoded back through PyAV:
every frame there, the first frame's pixels within the codec's tolerance, the frames' transfer (linear
or sRGB) tagged; bad frame sets refused with a message, no traceback and no partial video."""

import os
import pathlib
import subprocess
import sys

import av
import numpy as np
import pytest
from PIL import Image

ROOT = pathlib.Path(__file__).resolve().parents[2]
TRACER = os.environ.get("TRACER_BIN", str(ROOT / "build" / "release" / "tracer"))
# Odd sizes (a 4:2:0 video pads them), a moving ball on a checkered floor.
SCENE = """render { width 33 height 25 }
camera { eye (0, 2, 6) lookat (0, 0, 0) fovy 50 }
light { position (3, 5, 4) }
plane { point (0, -1, 0) normal (0, 1, 0) material { kd checker { even 0.9 odd 0.1 } } }
sphere { center (2 * clock - 1, 0, 0) radius 1 material { kd (0.9, 0.3, 0.1) ks 0.5 n 20 } }
"""
LINEAR, SRGB = 8, 13  # FFmpeg's transfer characteristics


def video(*arguments):
    command = [sys.executable, "-m", "tracer_tools", "video", *map(str, arguments)]
    environment = {**os.environ, "PYTHONPATH": str(ROOT / "tools")}
    return subprocess.run(command, capture_output=True, text=True, env=environment, cwd=ROOT)


@pytest.fixture
def frames(tmp_path):
    """Renders 6 frames of SCENE: the pattern of their names, given tracer's extra options."""

    def make(*options, folder="frames"):
        (tmp_path / folder).mkdir()
        scene = tmp_path / "scene.scn"
        scene.write_text(SCENE)
        pattern = tmp_path / folder / "f_###.png"
        subprocess.run([TRACER, str(scene), "-q", "--frames", "6", "-o", str(pattern), *options], check=True)
        return pattern

    return make


def decoded(path):
    """The video's frames (RGB) and its transfer characteristic, through PyAV."""
    with av.open(str(path)) as container:
        transfer = container.streams.video[0].codec_context.color_trc
        return [frame.to_ndarray(format="rgb24") for frame in container.decode(video=0)], transfer


def first_frame(pattern):
    return np.asarray(Image.open(str(pattern).replace("###", "000")).convert("RGB")).astype(int)


@pytest.mark.parametrize("extension", [".mp4", ".webm"])
def test_frames_round_trip_within_the_codecs_tolerance(frames, tmp_path, extension):
    pattern = frames()
    out = tmp_path / f"ball{extension}"
    result = video(pattern, "-o", out, "--fps", 12)
    assert result.returncode == 0, result.stderr
    images, transfer = decoded(out)
    assert len(images) == 6
    assert images[0].shape == (26, 34, 3)  # padded to even sizes
    error = np.abs(images[0][:25, :33].astype(int) - first_frame(pattern))
    assert error.mean() < 4 and np.percentile(error, 90) < 12, (error.mean(), np.percentile(error, 90))
    assert transfer == LINEAR  # tracer's default frames are linear, and the video says so
    assert not np.array_equal(images[0], images[5])  # the ball moved
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


def test_the_transfer_of_srgb_frames_is_kept_and_linear_ones_can_be_reencoded(frames, tmp_path):
    srgb_frames = frames("--encoding", "srgb", folder="srgb")
    result = video(srgb_frames, "-o", tmp_path / "srgb.mp4")
    assert result.returncode == 0, result.stderr
    images, transfer = decoded(tmp_path / "srgb.mp4")
    assert transfer == SRGB
    linear_frames = frames(folder="linear")
    result = video(linear_frames, "-o", tmp_path / "curved.mp4", "--encoding", "srgb")
    assert result.returncode == 0, result.stderr
    curved, transfer = decoded(tmp_path / "curved.mp4")
    assert transfer == SRGB
    # The re-encoded linear frames look like the frames tracer encoded to sRGB itself (8-bit steps apart).
    error = np.abs(curved[0][:25, :33].astype(int) - first_frame(srgb_frames))
    assert error.mean() < 6, error.mean()


def test_bad_frame_sets_are_refused_without_a_partial_video(frames, tmp_path):
    pattern = frames()
    gap = tmp_path / "gap"
    gap.mkdir()
    for number in (0, 1, 3):
        (gap / f"f_{number:03d}.png").write_bytes(pathlib.Path(str(pattern).replace("###", "000")).read_bytes())
    odd = tmp_path / "odd"
    odd.mkdir()
    (odd / "f_000.png").write_bytes(pathlib.Path(str(pattern).replace("###", "000")).read_bytes())
    Image.new("RGB", (10, 10)).save(odd / "f_001.png")
    (tmp_path / "broken").mkdir()
    (tmp_path / "broken" / "f_000.png").write_bytes(b"\x89PNG not really")
    cases = [
        ([gap / "f_###.png", "-o", tmp_path / "v.mp4"], "frame 2 of", 3),
        ([tmp_path / "frames" / "f.png", "-o", tmp_path / "v.mp4"], "no number field", 2),
        ([tmp_path / "nothing_###.png", "-o", tmp_path / "v.mp4"], "no frames match", 3),
        ([pattern, "-o", tmp_path / "v.avi"], ".mp4 or .webm", 2),
        ([pattern, "-o", tmp_path / "missing" / "v.mp4"], "no such folder", 3),
        ([odd / "f_###.png", "-o", tmp_path / "v.mp4"], "share one size", 2),
        ([tmp_path / "broken" / "f_###.png", "-o", tmp_path / "v.mp4"], "cannot read", 3),
        ([pattern, "-o", tmp_path / "v.mp4", "--fps", "0"], "--fps", 2),
    ]
    for arguments, words, code in cases:
        result = video(*arguments)
        assert result.returncode == code, (arguments, result.stderr)
        assert words in result.stderr, (arguments, result.stderr)
        assert "Traceback" not in result.stderr and "internal error" not in result.stderr
    assert not (tmp_path / "v.mp4").exists() and not any(p.name.startswith(".v") for p in tmp_path.iterdir())
