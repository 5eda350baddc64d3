"""Issue 54's cost targets for patterns, side by side on this machine (2 threads):

1. task2 with its floor a checker against task2 as it is (plain floor): render times alternated
   A B A B, the median of the per-pair ratios (target <= 1.10);
2. a scene whose image pattern reads a 4,096 x 4,096 8-bit PNG against the same scene reading a
   1 x 1 PNG: the extra wall time of a 1 x 1 render, which loads every file (target <= 0.3 s), and
   the bytes a texel the texels are held in (`tracer --stats`'s image line; target <= 4), and the
   extra peak memory of the whole process while it loads them (OpenImageIO's decoding buffer too);
3. scenes/whitted1980.scn against POV-Ray 3.7: tracer's render time over POV-Ray's reported trace
   time, alternated (target: at least 3x faster, a ratio <= 0.333).

    tools/bench patterns [--pairs 7]

The report goes to standard output, as committed in docs/bench/bench-patterns.md.
"""

import pathlib
import re
import statistics
import struct
import subprocess
import tempfile
import time
import zlib

from tracer_tools import ROOT
from tracer_tools.bench.common import TRACER, alternated, targets_main
from tracer_tools.bench.versus import THREADS, tracer_render_seconds, versus_povray

CHECKERED_FLOOR = "material matte   { ka 0.1  kd checker { even 1 odd 0.5 }  ks 0  km 0    n 0 }"


def checkered_task2(folder: pathlib.Path, pairs: int) -> dict:
    plain = ROOT / "scenes" / "task2.scn"
    text = plain.read_text()
    matte = "material matte   { ka 0.1  kd 1  ks 0  km 0    n 0 }"
    assert matte in text, "task2's matte material changed: update the benchmark"
    checkered = folder / "task2_checkered.scn"
    checkered.write_text(text.replace(matte, CHECKERED_FLOOR))
    times = alternated(
        lambda: tracer_render_seconds(checkered, folder), lambda: tracer_render_seconds(plain, folder), pairs
    )
    return {"ratio": times["ratio"], "plain": times["b"], "checkered": times["a"], "ratios": times["ratios"]}


def write_png(path: pathlib.Path, size: int) -> None:
    """An 8-bit RGB PNG of size x size texels: a smooth ramp with fine stripes (not one colour, so
    that it is a real decode), compressed fast."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    row_pattern = bytes(
        (x * 255 // max(1, size - 1)) if c == 0 else (x * 7) & 255 if c == 1 else 128
        for x in range(size)
        for c in range(3)
    )
    raw = b"".join(b"\x00" + row_pattern for _ in range(size))
    png = (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0))
        + chunk(b"IDAT", zlib.compress(raw, 1))
        + chunk(b"IEND", b"")
    )
    path.write_bytes(png)


def load_once(scene: pathlib.Path, folder: pathlib.Path) -> tuple[float, int]:
    """Wall seconds and peak resident kilobytes of one 1 x 1 render of `scene` (every file loaded)."""
    start = time.perf_counter()
    done = subprocess.run(
        ["/usr/bin/time", "-f", "%M", str(TRACER), str(scene), "-o", str(folder / "one.png"), "--threads", "1"],
        capture_output=True,
        text=True,
        check=True,
    )
    seconds = time.perf_counter() - start
    return seconds, int(done.stderr.strip().splitlines()[-1])


def texture_load(folder: pathlib.Path, pairs: int) -> dict:
    size = 4096
    write_png(folder / "big.png", size)
    write_png(folder / "small.png", 1)
    scenes = {}
    for name in ("big", "small"):
        scenes[name] = folder / f"{name}.scn"
        scenes[name].write_text(
            "render { width 1 height 1 }\ncamera { eye (0, 0, 1) lookat (0, 0, 0) }\n"
            "quad { corner (-1, -1, 0) edge1 (2, 0, 0) edge2 (0, 2, 0)\n"
            f'  material {{ ka image {{ file "{name}.png" }} }} }}\n'
        )
    extra_seconds, extra_kb = [], []
    for _ in range(pairs):
        big_s, big_kb = load_once(scenes["big"], folder)
        small_s, small_kb = load_once(scenes["small"], folder)
        extra_seconds.append(big_s - small_s)
        extra_kb.append(big_kb - small_kb)
    texels = size * size
    stats = subprocess.run(
        [str(TRACER), str(scenes["big"]), "-o", str(folder / "one.png"), "--threads", "1", "--stats"],
        capture_output=True,
        text=True,
        check=True,
    )
    held = float(re.search(r"\(([0-9.]+) bytes a texel\)", stats.stderr).group(1))
    return {
        "seconds": statistics.median(extra_seconds),
        "peak_per_texel": statistics.median(extra_kb) * 1024 / texels,
        "held_per_texel": held,
        "file_mb": (folder / "big.png").stat().st_size / 1e6,
    }


def main() -> int:
    args = targets_main("patterns", __doc__, THREADS)
    with tempfile.TemporaryDirectory() as name:
        folder = pathlib.Path(name)
        floor = checkered_task2(folder, args.pairs)
        print("| target | measured | met |\n|---|---|---|")
        print(
            f"| task2 with a checkered floor <= 1.10x task2's time | {floor['ratio']:.3f}x "
            f"({floor['checkered']:.3f} s against {floor['plain']:.3f} s; pairs "
            f"{', '.join(f'{r:.3f}' for r in floor['ratios'])}) | {'yes' if floor['ratio'] <= 1.10 else 'no'} |",
            flush=True,
        )
        load = texture_load(folder, args.pairs)
        print(
            f"| a 4096 x 4096 image texture loads within 0.3 s | {load['seconds']:.3f} s more than a 1 x 1 one "
            f"(a {load['file_mb']:.1f} MB PNG) | {'yes' if load['seconds'] <= 0.3 else 'no'} |"
        )
        print(
            f"| held in at most 4 bytes a texel (8-bit files) | {load['held_per_texel']:.2f} bytes a texel held; "
            f"{load['peak_per_texel']:.2f} of extra peak memory while loading (OpenImageIO's PNG reader decodes "
            f"the whole picture into a buffer of its own first) | {'yes' if load['held_per_texel'] <= 4 else 'no'} |",
            flush=True,
        )
        whitted = versus_povray(ROOT / "scenes" / "whitted1980.scn", args.pairs, folder)
        print(
            f"| Whitted's scene >= 3x faster than POV-Ray's trace | {1 / whitted['ratio']:.1f}x "
            f"(tracer {whitted['tracer_s']:.3f} s, POV-Ray {whitted['povray_s']:.3f} s; "
            f"ratio {whitted['ratio']:.3f}) | "
            f"{'yes' if whitted['ratio'] <= 1 / 3 else 'no'} |"
        )
    return 0
