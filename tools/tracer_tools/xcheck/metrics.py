"""How far one image is from another: error figures, a heat map and a side-by-side picture."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from .images import to_8bit

# Heat-map colours by the largest channel difference in 8-bit levels.
HEAT_BINS = [  # (more than this many levels, colour, legend)
    (0, (70, 70, 200), "1-2 levels"),
    (2, (240, 200, 40), "3-8 levels"),
    (8, (230, 30, 30), "over 8 levels"),
]


@dataclasses.dataclass
class Comparison:
    """Error of a test image against a reference. Float figures use both images clamped to
    [0, 1] (what an 8-bit file shows); level figures use the 8-bit images, per pixel the
    largest difference over R, G and B."""

    pixels: int
    rmse: float
    psnr: float  # dB; inf for identical images
    over_1: float  # share of pixels (0..1) differing by more than 1 level
    over_2: float
    over_8: float
    max_levels: int
    flip_mean: float  # NVIDIA FLIP (LDR), mean over the image; 0 = identical

    def as_dict(self) -> dict:
        return dataclasses.asdict(self)

    def summary(self) -> str:
        """A few lines for people."""
        psnr = "inf" if math.isinf(self.psnr) else f"{self.psnr:.2f}"
        count = lambda share: f"{share * 100:.4f}% ({round(share * self.pixels)} px)"  # noqa: E731
        return (
            f"RMSE {self.rmse:.6f}   PSNR {psnr} dB   FLIP mean {self.flip_mean:.6f}\n"
            f"pixels over 1 level: {count(self.over_1)}   over 2: {count(self.over_2)}   "
            f"over 8: {count(self.over_8)}   largest: {self.max_levels} levels"
        )


def level_differences(reference: np.ndarray, test: np.ndarray) -> np.ndarray:
    """Per pixel, the largest channel difference between the 8-bit images (H x W ints)."""
    return np.abs(to_8bit(reference).astype(np.int16) - to_8bit(test).astype(np.int16)).max(axis=2)


def flip_mean(reference: np.ndarray, test: np.ndarray) -> float:
    """Mean FLIP error of the clamped images, read as display values (tracer writes no gamma)."""
    import flip_evaluator

    _, mean, _ = flip_evaluator.evaluate(
        np.clip(reference, 0, 1).astype(np.float32), np.clip(test, 0, 1).astype(np.float32), "LDR", applyMagma=False
    )
    return float(mean)


def compare(reference: np.ndarray, test: np.ndarray) -> Comparison:
    """Comparison of two float H x W x 3 images of the same size."""
    if reference.shape != test.shape:
        raise ValueError(f"image sizes differ: {reference.shape} and {test.shape}")
    a = np.clip(reference.astype(np.float64), 0, 1)
    b = np.clip(test.astype(np.float64), 0, 1)
    rmse = float(np.sqrt(np.mean((a - b) ** 2)))
    levels = level_differences(reference, test)
    return Comparison(
        pixels=int(levels.size),
        rmse=rmse,
        psnr=math.inf if rmse == 0 else 20 * math.log10(1.0 / rmse),
        over_1=float(np.mean(levels > 1)),
        over_2=float(np.mean(levels > 2)),
        over_8=float(np.mean(levels > 8)),
        max_levels=int(levels.max()),
        flip_mean=flip_mean(reference, test),
    )


def heat_map(reference: np.ndarray, test: np.ndarray) -> np.ndarray:
    """An 8-bit image: the reference darkened to a quarter, every pixel that differs by more
    than 0 levels painted by HEAT_BINS."""
    levels = level_differences(reference, test)
    picture = (to_8bit(reference).astype(np.float32) * 0.25).astype(np.uint8)
    for threshold, colour, _ in HEAT_BINS:
        picture[levels > threshold] = colour
    return picture


def _font(height: int) -> ImageFont.ImageFont:
    return ImageFont.load_default(size=max(10, height // 40))


def _labelled(picture: np.ndarray, label: str) -> np.ndarray:
    image = Image.fromarray(picture, "RGB")
    ImageDraw.Draw(image).text(
        (6, 4), label, fill=(255, 255, 255), font=_font(image.height), stroke_width=2, stroke_fill=(0, 0, 0)
    )
    return image


def side_by_side(reference: np.ndarray, test: np.ndarray, reference_label: str, test_label: str) -> np.ndarray:
    """One 8-bit image: reference | test | heat map, labelled, with the heat map's legend."""
    heat = _labelled(heat_map(reference, test), "differences (8-bit levels)")
    draw, font = ImageDraw.Draw(heat), _font(heat.height)
    line = font.size + 4
    for row, (_, colour, legend) in enumerate(HEAT_BINS, start=1):
        draw.rectangle((6, 6 + line * row, 6 + font.size, 6 + line * row + font.size), fill=colour)
        draw.text((12 + font.size, 4 + line * row), legend, fill=(255, 255, 255), font=font)
    parts = [_labelled(to_8bit(reference), reference_label), _labelled(to_8bit(test), test_label), heat]
    width, height = parts[0].size
    whole = Image.new("RGB", (3 * width, height))
    for index, part in enumerate(parts):
        whole.paste(part, (index * width, 0))
    return np.asarray(whole)
