"""Tiles kept beside a job's output while it renders, so that a job interrupted (Ctrl-C, a failed tile, a
lost cluster) and run again renders only the tiles it lacks.

The folder `.NAME.farm/` beside the output NAME holds `manifest.json` (what the image is: the tracer
executable's and every input file's SHA-256, tracer's arguments, the frame and the tile size) and one
`.npy` file per finished tile, each written atomically. A run whose manifest differs (a scene, an included
file, a mesh or tracer changed) starts over; the folder is removed once the image is written. Every pixel
comes from tracer alone, so the image is the one an uninterrupted run writes.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import tempfile
from collections.abc import Callable
from typing import BinaryIO

import numpy as np

from tracer_tools.farm.jobs import Job
from tracer_tools.farm.tiles import Region

MANIFEST = "manifest.json"
VERSION = 1


def folder_of(output: str) -> str:
    """The folder that keeps `output`'s finished tiles."""
    folder, name = os.path.split(os.path.abspath(output))
    return os.path.join(folder, f".{name}.farm")


def file_digest(path: str) -> str:
    """SHA-256 of a file's bytes, read in blocks."""
    digest = hashlib.sha256()
    with open(path, "rb") as file:
        for block in iter(lambda: file.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def identity(tracer: str, job: Job) -> dict:
    """What the job's image depends on, as the manifest records it (the tile size aside)."""
    inputs = [job.scene, *job.inputs]
    return {
        "version": VERSION,
        "tracer": file_digest(tracer),
        "arguments": job.tracer_arguments(),
        "frame": [job.width, job.height],
        "float": job.is_float(),
        "inputs": {os.path.abspath(path): file_digest(path) for path in inputs},
    }


class TileStore:
    """The finished tiles of one job, on disk beside its output."""

    def __init__(self, output: str, manifest: dict) -> None:
        self.folder = folder_of(output)
        self.manifest = manifest  # identity(...) plus "tile"
        self.created = False

    def resume(self, tile: int | None, default_tile: int) -> tuple[int, dict[Region, np.ndarray]]:
        """The tile size to use and the tiles kept by an earlier run of the same job (none if it differs,
        or if `tile` asks for another size); a differing folder is cleared."""
        kept: dict[Region, np.ndarray] = {}
        earlier = self._read_manifest()
        same = earlier is not None and {k: v for k, v in earlier.items() if k != "tile"} == self.manifest
        if same and (tile is None or tile == earlier["tile"]):
            self.manifest["tile"] = earlier["tile"]
            self.created = True
            for name in os.listdir(self.folder):
                region = region_of(name)
                if region is not None:
                    pixels = self._load(name, region)
                    if pixels is not None:
                        kept[region] = pixels
            return earlier["tile"], kept
        if os.path.isdir(self.folder):
            shutil.rmtree(self.folder)
        self.manifest["tile"] = tile or default_tile
        return self.manifest["tile"], kept

    def keep(self, region: Region, pixels: np.ndarray) -> None:
        """Saves a finished tile (atomically: a file is whole or absent)."""
        if not self.created:
            os.makedirs(self.folder, exist_ok=True)
            self._write(MANIFEST, lambda file: file.write(json.dumps(self.manifest, indent=1).encode()))
            self.created = True
        self._write(tile_name(region), lambda file: np.save(file, pixels, allow_pickle=False))

    def remove(self) -> None:
        """Drops the folder: the image is written."""
        shutil.rmtree(self.folder, ignore_errors=True)

    def _read_manifest(self) -> dict | None:
        try:
            with open(os.path.join(self.folder, MANIFEST), encoding="utf-8") as file:
                manifest = json.load(file)
            return manifest if isinstance(manifest, dict) and isinstance(manifest.get("tile"), int) else None
        except (OSError, ValueError):
            return None

    def _load(self, name: str, region: Region) -> np.ndarray | None:
        """A kept tile's pixels, or None if the file is not a tile of this size and type."""
        try:
            pixels = np.load(os.path.join(self.folder, name), allow_pickle=False)
        except (OSError, ValueError):
            return None
        dtype = np.float32 if self.manifest["float"] else np.uint8
        return pixels if pixels.shape == (region.height, region.width, 3) and pixels.dtype == dtype else None

    def _write(self, name: str, write: Callable[[BinaryIO], object]) -> None:
        handle, temporary = tempfile.mkstemp(prefix=".part.", dir=self.folder)
        try:
            with os.fdopen(handle, "wb") as file:
                write(file)
            os.replace(temporary, os.path.join(self.folder, name))
        except BaseException:
            if os.path.exists(temporary):
                os.unlink(temporary)
            raise


def tile_name(region: Region) -> str:
    return f"tile-{region.x0}-{region.y0}-{region.width}-{region.height}.npy"


def region_of(name: str) -> Region | None:
    """The region a kept tile's file name gives, or None for any other file."""
    if not (name.startswith("tile-") and name.endswith(".npy")):
        return None
    fields = name[len("tile-") : -len(".npy")].split("-")
    if len(fields) != 4 or not all(field.isdigit() for field in fields):
        return None
    return Region(*(int(field) for field in fields))
