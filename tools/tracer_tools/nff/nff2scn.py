"""tools/nff2scn: converts an NFF file (Eric Haines' Neutral File Format) into a tracer scene.

    tools/nff2scn balls.nff -o scenes/spd/balls.scn

writes balls.scn and, beside it, the folder balls_meshes/ with the OBJ files it names (polygons
by material, one unit cone per radius ratio). The rules are in nff/convert.py. Errors are
`file:line:col: error: ...` with the line and a caret, exit status 1; nothing is written then.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import shutil
import stat
import sys
import tempfile
import time

from tracer_tools import option_types

from . import convert, reader

MAX_INPUT_BYTES = 1 << 30


def _read_input(path: str) -> str:
    """The file's text; a SystemExit with a message if it is not a readable regular file."""
    try:
        with open(path, "rb", opener=lambda p, flags: os.open(p, flags | os.O_NONBLOCK)) as file:
            info = os.fstat(file.fileno())
            if not stat.S_ISREG(info.st_mode):
                raise SystemExit(f"{path}: error: not a regular file")
            if info.st_size > MAX_INPUT_BYTES:
                raise SystemExit(f"{path}: error: {info.st_size:,} bytes, more than the {MAX_INPUT_BYTES:,} allowed")
            data = file.read(MAX_INPUT_BYTES + 1)
    except OSError as error:
        raise SystemExit(f"{path}: error: cannot read it: {error.strerror}") from None
    return data.decode("latin-1")  # NFF is ASCII; any other byte is then reported as a bad word


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _publish(staging: pathlib.Path, scn_path: pathlib.Path, meshes_name: str) -> None:
    """Moves the staged meshes folder and .scn into place, each replacing the old one whole."""
    folder = scn_path.parent / meshes_name
    old = None
    if folder.exists():
        old = folder.with_name(f".{meshes_name}.old.{os.getpid()}")
        folder.rename(old)
    (staging / meshes_name).rename(folder)
    if old is not None:
        shutil.rmtree(old)
    staged_scn = staging / scn_path.name
    with open(staged_scn, "rb+") as file:
        os.fsync(file.fileno())
    os.replace(staged_scn, scn_path)


def convert_file(
    nff_path: str | pathlib.Path,
    scn_path: str | pathlib.Path,
    corner_rays: bool = False,
    max_error_pixels: float = 0.1,
    cones: str = "analytic",
) -> dict:
    """Converts an NFF file, writing scn_path and its meshes folder; prints warnings on stderr.

    Returns the conversion's summary (counts, and `seconds`: reading, converting and writing);
    raises reader.NffError (nothing written) or SystemExit for a file it cannot read."""
    started = time.perf_counter()
    scn_path = pathlib.Path(scn_path)
    text = _read_input(nff_path)
    meshes_name = f"{scn_path.stem}_meshes"
    staging = pathlib.Path(tempfile.mkdtemp(prefix=f".{scn_path.stem}.", dir=scn_path.parent))
    try:
        writer = convert.Writer(staging, meshes_name, corner_rays, max_error_pixels, cones)
        try:
            scene = reader.read_nff(nff_path, text, writer)
        finally:
            writer.close()
        summary = writer.finish(scene, staging / scn_path.name)
        os.chmod(staging / scn_path.name, 0o666 & ~_umask())
        for message in scene.warnings:
            print(message, file=sys.stderr)
        for word, message in writer.warnings:
            print(scene.source.diagnostic("warning", word, message), file=sys.stderr)
        if writer.more_warnings:
            print(f"{nff_path}: note: {writer.more_warnings:,} more warnings not shown", file=sys.stderr)
        _publish(staging, scn_path, meshes_name)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return {**summary, "seconds": time.perf_counter() - started}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="tools/nff2scn", description=__doc__.split("\n")[0])
    parser.add_argument("nff", type=option_types.existing_file, help="the NFF file")
    parser.add_argument("-o", "--output", type=option_types.output_file, required=True, help="the .scn file to write")
    parser.add_argument(
        "--corner-rays",
        action="store_true",
        help="render (N+1) x (N+1) rays through the pixel corners (upstream's testing procedure; "
        "average 2 x 2 blocks for the N x N image)",
    )
    parser.add_argument(
        "--cones",
        choices=("analytic", "mesh"),
        default="analytic",
        help="cones and cylinders as tracer's own cones (default), or tessellated into meshes (to compare)",
    )
    parser.add_argument(
        "--max-error-pixels",
        type=option_types.real_number(0),
        default=0.1,
        help="largest outline error of a tessellated cone (pixels)",
    )
    args = parser.parse_args(argv)
    if args.output.suffix != ".scn":
        parser.error(f"the output must end in .scn: {args.output}")
    if not 0 < args.max_error_pixels <= 100:
        parser.error("--max-error-pixels must be in (0, 100]")
    if not args.output.parent.is_dir():
        parser.error(f"the output's folder does not exist: {args.output.parent}")

    try:
        summary = convert_file(args.nff, args.output, args.corner_rays, args.max_error_pixels, args.cones)
    except reader.NffError as error:
        print(error, file=sys.stderr)
        return 1
    print(
        f"{args.output}: {summary['spheres']} spheres, {summary['polygons']} polygons "
        f"({summary['triangles']} triangles), {summary['cones']} cones"
        + (f" (sides by radius ratio: {summary['cone_sides']})" if summary["cone_sides"] else "")
        + f", {summary['lights']} lights, "
        f"{summary['materials']} materials; {summary['seconds']:.2f} s",
        file=sys.stderr,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
