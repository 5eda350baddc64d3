"""Tile files in, the assembled image out (OpenImageIO), written atomically."""

from __future__ import annotations

import os
import tempfile

import numpy as np
import OpenImageIO as oiio


def decode_ppm(data: bytes) -> np.ndarray:
    """A binary 8-bit PPM file's pixels (height x width x 3), read without a copy of the file."""
    fields = data[:64].split(maxsplit=4)
    if len(fields) < 4 or fields[0] != b"P6" or fields[3] != b"255":
        raise ValueError("a tile came back as something other than an 8-bit binary PPM file")
    width, height = int(fields[1]), int(fields[2])
    size = width * height * 3
    if len(data) < size + 11:
        raise ValueError(f"a {width} x {height} tile came back with only {len(data)} bytes")
    return np.frombuffer(data, dtype=np.uint8, count=size, offset=len(data) - size).reshape(height, width, 3)


def decode_tile(data: bytes, suffix: str, dtype: np.dtype) -> np.ndarray:
    """A tile file's pixels (height x width x 3) in the canvas's type; its data window only."""
    if suffix == ".ppm":
        return decode_ppm(data)
    with tempfile.NamedTemporaryFile(suffix=suffix) as file:
        file.write(data)
        file.flush()
        image = oiio.ImageInput.open(file.name)
        if image is None:
            raise ValueError(f"a tile came back unreadable: {oiio.geterror()}")
        try:
            pixels = image.read_image(oiio.UINT8 if dtype == np.uint8 else oiio.FLOAT)
        finally:
            image.close()
    if pixels is None:
        raise ValueError("a tile came back unreadable")
    return np.asarray(pixels, dtype=dtype).reshape(image.spec().height, image.spec().width, -1)[:, :, :3]


def write_atomically(path: str, pixels: np.ndarray, srgb: bool = False) -> None:
    """Writes the image beside `path` under a temporary name, then renames it: `path` is either
    untouched or the whole image, never a partial file. `srgb`: 8-bit pixels are sRGB-encoded, and
    the file says so where its format can (a PNG's sRGB chunk), as tracer's own files do."""
    folder, name = os.path.split(os.path.abspath(path))
    extension = os.path.splitext(name)[1]
    handle, temporary = tempfile.mkstemp(prefix=f".{name}.", suffix=extension, dir=folder)
    os.close(handle)
    try:
        output = oiio.ImageOutput.create(temporary)
        if output is None:
            raise OSError(f"cannot write '{path}': {oiio.geterror()}")
        height, width = pixels.shape[:2]
        spec = oiio.ImageSpec(width, height, 3, oiio.UINT8 if pixels.dtype == np.uint8 else oiio.FLOAT)
        if srgb and pixels.dtype == np.uint8:
            spec.attribute("oiio:ColorSpace", "sRGB")
        if not (output.open(temporary, spec) and output.write_image(pixels) and output.close()):
            raise OSError(f"cannot write '{path}': {output.geterror()}")
        os.chmod(temporary, 0o644)
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise
