"""Image files: tracer's float output (EXR) in, 8-bit PNGs out."""

from __future__ import annotations

import pathlib
import zlib

import numpy as np
from PIL import Image


def read_exr(path: str | pathlib.Path) -> np.ndarray:
    """A float image file (tracer writes EXR unclamped) as a float32 H x W x 3 array, top row
    first; read with Mitsuba's Bitmap (OpenEXR inside)."""
    import mitsuba as mi  # a variant is set by whoever imported xcheck.mitsuba_render

    bitmap = mi.Bitmap(str(path)).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
    return np.array(bitmap, dtype=np.float32)


def write_exr(path: str | pathlib.Path, image: np.ndarray) -> None:
    """Writes a float H x W x 3 image as EXR (Mitsuba's Bitmap)."""
    import mitsuba as mi

    mi.Bitmap(np.ascontiguousarray(image, dtype=np.float32), mi.Bitmap.PixelFormat.RGB).write(str(path))


def to_8bit(image: np.ndarray) -> np.ndarray:
    """tracer's 8-bit rule: clamp to [0, 1], round(255 v), no gamma."""
    return np.round(np.clip(image, 0.0, 1.0) * 255.0).astype(np.uint8)


def srgb_encoded(image: np.ndarray) -> np.ndarray:
    """The sRGB curve (IEC 61966-2-1) of linear values, as tracer's `encoding srgb` applies it."""
    v = np.clip(image.astype(np.float64), 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


def write_png(path: str | pathlib.Path, image: np.ndarray, srgb: bool = False) -> None:
    """Writes an 8-bit (or float, converted by to_8bit) H x W x 3 image; `srgb`: a float image
    encoded by the sRGB curve first, and the file given an sRGB chunk, as tracer writes it."""
    if image.dtype != np.uint8:
        image = to_8bit(srgb_encoded(image) if srgb else image)
    Image.fromarray(image, "RGB").save(path)
    if srgb:  # the sRGB chunk (rendering intent 0) right after IHDR, which PIL does not write
        data = pathlib.Path(path).read_bytes()
        chunk = b"sRGB\x00"
        header_end = 8 + 12 + int.from_bytes(data[8:12], "big")
        marked = len(chunk[4:]).to_bytes(4, "big") + chunk + zlib.crc32(chunk).to_bytes(4, "big")
        pathlib.Path(path).write_bytes(data[:header_end] + marked + data[header_end:])
