"""Tiles kept beside a job's output while it renders, so that a job interrupted (Ctrl-C, a failed tile, a
lost cluster) and run again renders only the tiles it lacks.

The folder `.NAME.farm/` beside the output NAME holds `manifest.json` (what the image is: the tracer
executable's and every input file's SHA-256, tracer's arguments, the frame and the tile size) and one
`.npy` file per finished tile, each written atomically and named by its region and a digest of its bytes
and the manifest. A run whose manifest differs (a scene, an included file, a mesh or tracer changed)
starts over; the folder is removed once the image is written. Nothing kept is trusted: the manifest must
have exactly the expected fields and types and a tile size the run could use, and each tile must be a
regular file of its region's size whose digest matches; anything else is discarded with one line and
rendered again. Every pixel comes from tracer alone, so the image is the one an uninterrupted run writes.
"""

from __future__ import annotations

import functools
import hashlib
import io
import json
import os
import shutil
import sys
import tempfile

import numpy as np

from tracer_tools import option_types
from tracer_tools.farm.jobs import Job, JobError
from tracer_tools.farm.tiles import Region, split

MANIFEST = "manifest.json"
VERSION = 2  # 2: tiles named by their digest
MAX_MANIFEST_BYTES = 1 << 20
# A kept tile size is used again only if it makes at most this many times the tiles the run would
# make by default (a tampered "tile": 1 would split a frame into millions of tasks).
MOST_TILES_PER_DEFAULT = 64


def folder_of(output: str) -> str:
    """The folder that keeps `output`'s finished tiles."""
    folder, name = os.path.split(os.path.abspath(output))
    return os.path.join(folder, f".{name}.farm")


def file_digest(path: str) -> str:
    """SHA-256 of a file's bytes, read in blocks; the same file (path, size, modification time) is
    read once per run (10^5 jobs share one tracer)."""
    info = os.stat(path)
    return _digest_of(os.path.abspath(path), info.st_size, info.st_mtime_ns)


@functools.lru_cache(maxsize=4096)
def _digest_of(path: str, size: int, modified: int) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as file:
        for block in iter(lambda: file.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def input_digests(job: Job) -> dict[str, str]:
    """Each file the job's scene reads (the scene too), by absolute path, with its SHA-256."""
    return {os.path.abspath(path): file_digest(path) for path in [job.scene, *job.inputs]}


def identity(
    tracer: str,
    job: Job,
    inputs: dict[str, str] | None = None,
    tracer_digest: str | None = None,
    engine: str = "process",
) -> dict:
    """What the job's image depends on, as the manifest records it (the tile size aside): `tracer` is
    the file that renders (the executable, or the package's extension for the module engine);
    `inputs` and `tracer_digest`: input_digests(job) and file_digest(tracer), when already known
    (jobs of one scene share them)."""
    return {
        "version": VERSION,
        "tracer": file_digest(tracer) if tracer_digest is None else tracer_digest,
        "engine": engine,
        "arguments": job.tracer_arguments(),
        "frame": [job.width, job.height],
        "float": job.is_float(),
        "inputs": input_digests(job) if inputs is None else inputs,
    }


class TileStore:
    """The finished tiles of one job, on disk beside its output."""

    def __init__(self, output: str, manifest: dict) -> None:
        self.output = output
        self.folder = folder_of(output)
        self.manifest = manifest  # identity(...) plus "tile"
        self.created = False

    def resume(self, tile: int | None, default_tile: int) -> tuple[int, dict[Region, np.ndarray]]:
        """The tile size to use and the valid tiles kept by an earlier run of the same job (none if
        it differs, or if `tile` asks for another size); a differing folder is cleared."""
        self._check_folder()
        kept: dict[Region, np.ndarray] = {}
        earlier, problem = self._read_manifest(default_tile)
        if earlier is not None and (tile is None or tile == earlier["tile"]):
            self.manifest["tile"] = earlier["tile"]
            self.created = True
            names = os.listdir(self.folder)
            width, height = self.manifest["frame"]
            wanted = set(split(width, height, earlier["tile"]))
            tiles = [(name, region_of(name)) for name in names]
            for name, region in tiles:
                if region is not None and region[0] in wanted and (pixels := self._load(name, *region)) is not None:
                    kept[region[0]] = pixels
            discarded = sum(region is not None for _, region in tiles) - len(kept)
            if discarded:
                say(
                    f"{discarded} kept tile{'s' if discarded > 1 else ''} of {self.output} "
                    "not valid (not a regular file, or not its region's size or content): rendered again"
                )
            return earlier["tile"], kept
        if problem:
            say(f"the kept tiles of {self.output} are discarded: {problem}")
        if os.path.lexists(self.folder):
            shutil.rmtree(self.folder)
        self.manifest["tile"] = tile or default_tile
        return self.manifest["tile"], kept

    def keep(self, region: Region, pixels: np.ndarray) -> None:
        """Saves a finished tile (atomically: a file is whole or absent), named by its digest."""
        if not self.created:
            self._check_folder()
            os.makedirs(self.folder, exist_ok=True)
            self._write(MANIFEST, json.dumps(self.manifest, indent=1).encode())
            self.created = True
        buffer = io.BytesIO()
        np.save(buffer, pixels, allow_pickle=False)
        data = buffer.getvalue()
        self._write(tile_name(region, self._digest(data)), data)

    def remove(self) -> None:
        """Drops the folder: the image is written."""
        if os.path.isdir(self.folder) and not os.path.islink(self.folder):
            shutil.rmtree(self.folder, ignore_errors=True)

    def _check_folder(self) -> None:
        """The kept tiles' path must be the farm's folder or nothing: a link there is removed (never
        followed); another file is the user's, and the job stops before any tile."""
        if os.path.islink(self.folder):
            say(f"{self.folder} was a symbolic link, not the farm's folder of kept tiles: removed")
            os.unlink(self.folder)
        elif os.path.lexists(self.folder) and not os.path.isdir(self.folder):
            raise JobError(f"{self.folder} exists and is not the farm's folder of kept tiles: move it away", 3)

    def _read_manifest(self, default_tile: int) -> tuple[dict | None, str]:
        """The earlier run's manifest if it is this job's with a usable tile size, else None and why
        (empty when there is simply none)."""
        path = os.path.join(self.folder, MANIFEST)
        if not os.path.lexists(path):
            return None, ""
        try:
            earlier = json.loads(option_types.read_regular_file(path, MAX_MANIFEST_BYTES))
        except option_types.UnreadableFile as error:
            return None, str(error)
        except ValueError:
            return None, "its manifest is not JSON"
        if not isinstance(earlier, dict) or set(earlier) != {*self.manifest, "tile"}:
            return None, "its manifest does not have the expected fields"
        tile = earlier["tile"]
        if type(tile) is not int or not 1 <= tile <= 16384:
            return None, f"its tile size {str(tile)[:40]} is not a whole number from 1 to 16384"
        if (default_tile / tile) ** 2 > MOST_TILES_PER_DEFAULT:
            return (
                None,
                f"its tile size {tile} would make over {MOST_TILES_PER_DEFAULT} times the tiles of {default_tile}",
            )
        same = json.dumps({k: v for k, v in earlier.items() if k != "tile"}, sort_keys=True) == json.dumps(
            self.manifest, sort_keys=True
        )  # JSON's types too: true is not 1
        return (earlier, "") if same else (None, "")

    def _digest(self, data: bytes) -> str:
        """The digest that names a tile: its bytes and this job's manifest (a tile of another job or
        another run's tile size does not match)."""
        digest = hashlib.sha256(json.dumps(self.manifest, sort_keys=True).encode())
        digest.update(data)
        return digest.hexdigest()[:32]

    def _load(self, name: str, region: Region, digest: str) -> np.ndarray | None:
        """A kept tile's pixels, or None unless the file is a regular one of the region's size and
        type whose digest matches its name."""
        dtype = np.dtype(np.float32 if self.manifest["float"] else np.uint8)
        most = region.width * region.height * 3 * dtype.itemsize + 4096  # the pixels and the header
        try:
            data = option_types.read_regular_file(os.path.join(self.folder, name), most)
        except option_types.UnreadableFile:
            return None
        if self._digest(data) != digest:
            return None
        try:
            pixels = np.load(io.BytesIO(data), allow_pickle=False)
        except ValueError:
            return None
        return pixels if pixels.shape == (region.height, region.width, 3) and pixels.dtype == dtype else None

    def _write(self, name: str, data: bytes) -> None:
        handle, temporary = tempfile.mkstemp(prefix=".part.", dir=self.folder)
        try:
            with os.fdopen(handle, "wb") as file:
                file.write(data)
            os.replace(temporary, os.path.join(self.folder, name))
        except BaseException:
            if os.path.exists(temporary):
                os.unlink(temporary)
            raise


def say(line: str) -> None:
    print(f"farm: {line}", file=sys.stderr)


def tile_name(region: Region, digest: str) -> str:
    return f"tile-{region.x0}-{region.y0}-{region.width}-{region.height}-{digest}.npy"


def region_of(name: str) -> tuple[Region, str] | None:
    """The region and digest a kept tile's file name gives, or None for any other file."""
    if not (name.startswith("tile-") and name.endswith(".npy")):
        return None
    fields = name[len("tile-") : -len(".npy")].split("-")
    if len(fields) != 5 or not all(field.isdigit() and len(field) < 7 for field in fields[:4]):
        return None
    if len(fields[4]) != 32 or any(c not in "0123456789abcdef" for c in fields[4]):
        return None
    return Region(*(int(field) for field in fields[:4])), fields[4]
