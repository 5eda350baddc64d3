"""tools/mitsuba-render SCENE -o IMAGE: Mitsuba 3's image of a tracer scene (the plugins of
xcheck.plugins loaded), with the converted XML written beside the image as IMAGE.xml.
.exr keeps floats; other extensions get tracer's 8-bit rule (the scene's `encoding` too). Exit codes as
tools/crosscheck."""

from __future__ import annotations

import argparse
import pathlib
import sys
import tempfile

from tracer_tools import option_types

from . import run_reporting_errors, tracer_cli


def render(args: argparse.Namespace) -> int:
    """Renders and writes the image and its XML; returns the exit code."""
    scene = tracer_cli.dump_json(args.scene, tracer_cli.overrides(args.width, args.height, args.samples))
    from . import (
        images,
        mitsuba_render,  # first: it says clearly when Mitsuba is missing
    )

    with tempfile.TemporaryDirectory() as folder:
        image = mitsuba_render.render_scene(scene, folder)
        xml = (pathlib.Path(folder) / "scene.xml").read_text()
    args.output.with_name(args.output.name + ".xml").write_text(xml)
    if args.output.suffix.lower() == ".exr":
        images.write_exr(args.output, image)
    else:
        images.write_png(args.output, image, srgb=scene["render"].get("encoding") == "srgb")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="tools/mitsuba-render", description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", type=option_types.existing_file, help="the scene file (.scn)")
    parser.add_argument("-o", "--output", type=option_types.output_file, required=True, help="the image (.png, .exr)")
    parser.add_argument("--width", type=option_types.whole_number(1, 16384), help="image width (default: the scene's)")
    parser.add_argument(
        "--height", type=option_types.whole_number(1, 16384), help="image height (default: the scene's)"
    )
    parser.add_argument(
        "--samples", type=option_types.whole_number(1, 1 << 20), help="samples per pixel, N*N (default: the scene's)"
    )
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    return run_reporting_errors("mitsuba-render", lambda: render(args))


if __name__ == "__main__":
    sys.exit(main())
