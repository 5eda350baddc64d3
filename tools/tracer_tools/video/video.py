"""tools/video: the numbered frames of an animation (tracer --frames N -o frames/f_####.png) encoded
into one video through PyAV (FFmpeg's libraries): .mp4 (H.264) or .webm (VP9), written atomically.
(No .gif: its 256 colours want a palette made from the frames, which FFmpeg's palettegen filter makes
better than any fixed palette; encode the .mp4 to a GIF with FFmpeg if one is needed.)

    tools/video frames/f_####.png -o orbit.mp4 --fps 24

The video keeps the frames' transfer: frames written with tracer's sRGB encoding (--encoding srgb, a
PNG marked sRGB) are tagged sRGB, as players expect; tracer's default linear 8-bit frames are tagged
linear, and --encoding srgb re-encodes them with the sRGB curve (their dark steps then show: render
with --encoding srgb, or to .exr, for a video). Float frames (.exr) are always sRGB-encoded."""

from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile

import numpy as np

from tracer_tools import option_types

# Each output extension's container format, codec and pixel format.
CODECS = {
    ".mp4": ("mp4", "libx264", "yuv420p"),
    ".webm": ("webm", "libvpx-vp9", "yuv420p"),
}
# FFmpeg's transfer characteristics (AVColorTransferCharacteristic).
TRANSFER = {"linear": 8, "srgb": 13}
MOST_FRAMES = 1_000_000


class VideoError(Exception):
    """A problem with the frames or the output: the message, and the exit code."""

    def __init__(self, message: str, exit_code: int = 2) -> None:
        super().__init__(message)
        self.exit_code = exit_code


def frame_files(pattern: str) -> list[str]:
    """The files of `pattern` (its file name's last run of '#' standing for a frame number of at least
    that many digits), in frame order; VideoError if there are none or one is missing."""
    folder, name = os.path.split(pattern)
    runs = list(re.finditer(r"#+", name))
    if not runs:
        raise VideoError(f"'{pattern}' has no number field: name the frames as tracer -o does, e.g. f_####.png")
    run = runs[-1]
    matcher = re.compile(
        re.escape(name[: run.start()]) + r"(\d{%d,})" % len(run.group()) + re.escape(name[run.end() :]) + "$"
    )
    try:
        names = os.listdir(folder or ".")
    except OSError as error:
        raise VideoError(f"cannot read the folder '{folder or '.'}': {error.strerror}", 3) from error
    numbered = sorted((int(m.group(1)), n) for n in names if (m := matcher.match(n)))
    if not numbered:
        raise VideoError(f"no frames match '{pattern}'", 3)
    if len(numbered) > MOST_FRAMES:
        raise VideoError(f"{len(numbered)} frames match '{pattern}'; a video takes at most {MOST_FRAMES}")
    for (number, _), (next_number, _) in zip(numbered, numbered[1:], strict=False):
        if next_number != number + 1:
            raise VideoError(
                f"frame {number + 1} of '{pattern}' is missing (frames {numbered[0][0]} to "
                f"{numbered[-1][0]} are there otherwise)",
                3,
            )
    return [os.path.join(folder, n) for _, n in numbered]


def srgb_encoded(linear: np.ndarray) -> np.ndarray:
    """The sRGB curve (IEC 61966-2-1) of linear values, clamped to 0..1, as 8-bit values."""
    c = np.clip(linear.astype(np.float64), 0.0, 1.0)
    encoded = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.floor(encoded * 255 + 0.5).astype(np.uint8)


def read_frame(path: str) -> tuple[np.ndarray, str]:
    """A frame's 8-bit RGB pixels and their transfer ("linear" or "srgb")."""
    if path.lower().endswith((".exr", ".hdr")):
        import OpenImageIO as oiio

        image = oiio.ImageInput.open(path)
        if image is None:
            raise VideoError(f"cannot read '{path}': {oiio.geterror()}", 3)
        pixels = np.asarray(image.read_image(oiio.FLOAT))
        image.close()
        return srgb_encoded(pixels[:, :, :3]), "srgb"
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(path) as image:
            transfer = "srgb" if "srgb" in image.info else "linear"
            return np.asarray(image.convert("RGB")), transfer
    except (OSError, UnidentifiedImageError) as error:
        raise VideoError(f"cannot read '{path}': {error}", 3) from error


def even(pixels: np.ndarray) -> np.ndarray:
    """The frame with its last row and column repeated where its height or width is odd (4:2:0 video
    needs even sizes)."""
    height, width = pixels.shape[:2]
    return np.pad(pixels, ((0, height % 2), (0, width % 2), (0, 0)), mode="edge")


def encode(files: list[str], output: str, fps: float, quality: int, encoding: str | None) -> int:
    """Encodes the frames into `output` (atomically); the number of frames."""
    import av

    container_format, codec, pixel_format = CODECS[os.path.splitext(output)[1].lower()]
    folder, name = os.path.split(os.path.abspath(output))
    handle, temporary = tempfile.mkstemp(prefix=f".{name}.", suffix=os.path.splitext(name)[1], dir=folder)
    os.close(handle)
    try:
        with av.open(temporary, mode="w", format=container_format) as container:
            stream = None
            size = None
            for path in files:
                pixels, transfer = read_frame(path)
                if encoding == "srgb" and transfer == "linear":
                    pixels, transfer = srgb_encoded(pixels / 255.0), "srgb"
                if stream is None:
                    size = pixels.shape[:2]
                    stream = container.add_stream(codec, rate=round(fps) if fps == round(fps) else fps)
                    stream.height, stream.width = even(pixels).shape[:2]
                    stream.pix_fmt = pixel_format
                    stream.options = {"crf": str(quality)}
                    stream.codec_context.color_trc = TRANSFER[transfer]
                elif pixels.shape[:2] != size:
                    raise VideoError(
                        f"'{path}' is {pixels.shape[1]} x {pixels.shape[0]}; the first frame is "
                        f"{size[1]} x {size[0]}: a video's frames share one size"
                    )
                frame = av.VideoFrame.from_ndarray(np.ascontiguousarray(even(pixels)), format="rgb24")
                for packet in stream.encode(frame):
                    container.mux(packet)
            for packet in stream.encode():
                container.mux(packet)
        os.chmod(temporary, 0o644)
        os.replace(temporary, output)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise
    return len(files)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="tools/video", description=__doc__.split("\n\n")[0])
    parser.add_argument("frames", type=option_types.free_text, help="the frames' names, as tracer's -o: f_####.png")
    parser.add_argument("-o", "--output", type=option_types.output_file, required=True, help="the video: .mp4 or .webm")
    parser.add_argument(
        "--fps", type=option_types.real_number(0.1, 1000), default=24, help="frames a second (default 24)"
    )
    parser.add_argument(
        "--quality",
        type=option_types.whole_number(0, 51),
        default=18,
        help="the codec's constant rate factor: 0 lossless (H.264) to 51, lower is better (default 18)",
    )
    parser.add_argument("--encoding", choices=["srgb"], help="srgb: re-encode linear 8-bit frames with the sRGB curve")
    parser.add_argument("-q", "--quiet", action="store_true", help="no summary line")
    arguments = parser.parse_args(sys.argv[1:] if argv is None else argv)
    output = str(arguments.output)
    if os.path.splitext(output)[1].lower() not in CODECS:
        parser.error(f"-o {output}: the video's name ends in .mp4 or .webm")
    if not os.path.isdir(os.path.dirname(os.path.abspath(output))):
        print(f"video: error: cannot write '{output}': no such folder", file=sys.stderr)
        return 3
    import av

    try:
        count = encode(frame_files(arguments.frames), output, arguments.fps, arguments.quality, arguments.encoding)
    except av.FFmpegError as error:
        print(f"video: error: the encoder failed: {error}", file=sys.stderr)
        return 3
    except VideoError as error:
        print(f"video: error: {error}", file=sys.stderr)
        return error.exit_code
    if not arguments.quiet:
        print(f"video: wrote {output}: {count} frames at {arguments.fps:g} a second", file=sys.stderr)
    return 0
