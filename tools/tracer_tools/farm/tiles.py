"""Splitting a frame into tiles and putting the rendered tiles back together."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Region:
    """A window of the frame in pixels: columns x0 .. x0 + width - 1, rows y0 .. y0 + height - 1."""

    x0: int
    y0: int
    width: int
    height: int

    def text(self) -> str:
        return f"{self.x0} {self.y0} {self.width} {self.height}"


def tile_size_for(width: int, height: int, slots: int, tiles_per_slot: int = 16) -> int:
    """The side of square tiles giving each worker slot about `tiles_per_slot` tiles: enough that the
    last tiles leave workers idle briefly, few enough that each tile's fixed cost stays small."""
    wanted = max(1, slots * tiles_per_slot)
    return max(32, math.ceil(math.sqrt(width * height / wanted)))


def split(width: int, height: int, tile: int) -> list[Region]:
    """Tiles of `tile` x `tile` pixels covering the frame row by row (the last row and column smaller)."""
    if width < 1 or height < 1 or tile < 1:
        raise ValueError(f"cannot split a {width} x {height} frame into tiles of {tile} pixels")
    return [
        Region(x, y, min(tile, width - x), min(tile, height - y))
        for y in range(0, height, tile)
        for x in range(0, width, tile)
    ]


class Canvas:
    """The whole frame, filled tile by tile; knows when every pixel has arrived."""

    def __init__(self, width: int, height: int, dtype: np.dtype, tiles: int) -> None:
        self.pixels = np.zeros((height, width, 3), dtype=dtype)
        self.missing = tiles

    def paste(self, region: Region, pixels: np.ndarray) -> None:
        """Puts a tile's pixels (height x width x 3) at its place."""
        if pixels.shape != (region.height, region.width, 3):
            raise ValueError(f"tile {region.text()} came back as {pixels.shape[1]} x {pixels.shape[0]} pixels")
        self.pixels[region.y0 : region.y0 + region.height, region.x0 : region.x0 + region.width] = pixels
        self.missing -= 1

    def complete(self) -> bool:
        return self.missing == 0
