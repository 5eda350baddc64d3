"""tools/crosscheck SCENE: render a scene with tracer and with Mitsuba 3 (the plugins of
xcheck.plugins) or, with --with povray, POV-Ray 3.7 (xcheck.povray), report how far apart the
images are, and fail above a threshold.

Exit codes: 0 the images agree within the thresholds (or the peer cannot express the scene:
skipped, and said so); 1 they do not; 2 bad command line;
3 tracer rejected the scene (its diagnostics are printed); 4 Mitsuba 3 (or POV-Ray) is missing; 5 another
failure (a scene the cross-check cannot convert, a file that cannot be written, ...).
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import sys
from typing import TYPE_CHECKING

from tracer_tools import option_types

from . import PeerCannotExpress, progress, run_reporting_errors, tracer_cli

if TYPE_CHECKING:
    from .metrics import Comparison

DEFAULT_MAX_OVER_2 = 0.1  # percent of pixels more than 2 levels apart: the project's target


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="tools/crosscheck",
        description="Render SCENE with tracer and with Mitsuba 3 at the same resolution and samples "
        "per pixel; print RMSE, PSNR, FLIP and the share of pixels more than 1, 2 and 8 "
        "levels apart; write the images, a heat map and a side-by-side PNG.",
        epilog="Exit codes: 0 agree, 1 over a threshold, 2 bad command line, 3 scene errors, "
        "4 Mitsuba missing, 5 other failures.",
    )
    parser.add_argument("scene", type=option_types.existing_file, help="the scene file (.scn)")
    parser.add_argument(
        "--width",
        type=option_types.whole_number(1, 16384),
        help="image width (default: the scene's); alone, " "the height follows the scene's aspect ratio",
    )
    parser.add_argument(
        "--height", type=option_types.whole_number(1, 16384), help="image height (default: the scene's)"
    )
    parser.add_argument(
        "--samples", type=option_types.whole_number(1, 1 << 20), help="samples per pixel, N*N (default: the scene's)"
    )
    parser.add_argument(
        "--out",
        type=option_types.output_folder,
        help="folder for the images and report " "(default: out/crosscheck/<scene name>)",
    )
    parser.add_argument(
        "--max-over-2",
        type=option_types.real_number(-math.inf),
        default=DEFAULT_MAX_OVER_2,
        metavar="PERCENT",
        help=f"fail when more than PERCENT %% of the pixels differ by more than 2 "
        f"levels (default {DEFAULT_MAX_OVER_2})",
    )
    parser.add_argument(
        "--max-over-8",
        type=option_types.real_number(-math.inf),
        metavar="PERCENT",
        help="fail when more than PERCENT %% differ by more than 8 levels",
    )
    parser.add_argument("--max-rmse", type=option_types.real_number(-math.inf), help="fail when the RMSE is above this")
    parser.add_argument(
        "--max-flip", type=option_types.real_number(-math.inf), help="fail when the FLIP mean is above this"
    )
    parser.add_argument(
        "--with",
        dest="peer",
        choices=("mitsuba", "povray"),
        default="mitsuba",
        help="the other renderer: Mitsuba 3 with tracer's integrator as plugins (default), or POV-Ray 3.7",
    )
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    return parser.parse_args(argv)


def resolution_args(args: argparse.Namespace) -> list[str]:
    """tracer overrides for the requested size and samples (width alone keeps the aspect,
    which costs one more --dump-json)."""
    width, height = args.width, args.height
    if width is not None and height is None:
        render = tracer_cli.dump_json(args.scene)["render"]
        height = max(1, round(width * render["height"] / render["width"]))
    return tracer_cli.overrides(width=width, height=height, samples=args.samples)


def failures(comparison: Comparison, args: argparse.Namespace) -> list[str]:
    """The thresholds the comparison exceeds, as sentences."""
    checks = [
        ("pixels over 2 levels", comparison.over_2 * 100, args.max_over_2, "%"),
        ("pixels over 8 levels", comparison.over_8 * 100, args.max_over_8, "%"),
        ("RMSE", comparison.rmse, args.max_rmse, ""),
        ("FLIP mean", comparison.flip_mean, args.max_flip, ""),
    ]
    return [
        f"{name} {value:.6g}{unit} > {limit:g}{unit}"
        for name, value, limit, unit in checks
        if limit is not None and value > limit
    ]


def skipped(args: argparse.Namespace, out: pathlib.Path, reason: str) -> int:
    """Says why the scene is not checked (and writes it in the report): exit 0, no failure."""
    print(f"crosscheck: skipped: {reason}", file=sys.stderr)
    report = {"scene": str(args.scene), "skipped": reason, "failed": [], "output": str(out)}
    (out / "report.json").write_text(json.dumps(report, indent=2) + "\n")
    if args.json:
        print(json.dumps(report, indent=2))
    return 0


def crosscheck(args: argparse.Namespace) -> int:
    """Runs the whole check; returns the exit code."""
    # Step 1: the scene as tracer resolves it, with the requested size and samples. POV-Ray's
    # antialiasing is its own: a scene's supersampling is compared at one sample, and said so.
    extra = resolution_args(args)
    scene = tracer_cli.dump_json(args.scene, extra)
    render = scene["render"]
    uniform = render.get("antialias", "uniform") == "uniform"
    if args.peer == "povray" and args.samples is None and uniform and render["samples"] != 1:
        print(
            "crosscheck: note: POV-Ray's antialiasing is its own, not tracer's: comparing at 1 sample per "
            f"pixel (the scene asks for {render['samples']})",
            file=sys.stderr,
        )
        extra = [*extra, "--samples", "1"]
        scene = tracer_cli.dump_json(args.scene, extra)
    out = args.out or tracer_cli.ROOT / "out" / "crosscheck" / args.scene.stem
    out.mkdir(parents=True, exist_ok=True)
    print(f"crosscheck: the images and the report go to {out}", file=sys.stderr)

    # Step 2: both renders, as floats (the peer first: it may refuse the scene).
    from . import (
        images,
        metrics,
        mitsuba_render,  # first: it says clearly when Mitsuba is missing (and reads EXR)
    )

    peer_times = {}
    render = scene["render"]
    size = f"{render['width']}x{render['height']}, {render['samples']} spp"
    if args.peer == "povray":
        from . import povray

        peer, peer_name = "povray", "POV-Ray 3.7"
        with progress.step("crosscheck", f"rendering with {peer_name} ({size})"):
            peer_image, peer_times = povray.render_scene(scene, out)
        for note in peer_times["approximated"]:
            print(f"crosscheck: note: {note}", file=sys.stderr)
    else:
        peer, peer_name = "mitsuba", "Mitsuba 3"
        try:
            with progress.step("crosscheck", f"rendering with {peer_name} ({size})"):
                peer_image = mitsuba_render.render_scene(scene, out)
        except PeerCannotExpress as reason:
            return skipped(args, out, str(reason))
    with progress.step("crosscheck", "rendering with tracer"):
        tracer_image = tracer_cli.render_pixels(args.scene, extra)[0]
    images.write_exr(out / "tracer.exr", tracer_image)

    # Step 3: compare, write the pictures, report.
    with progress.step("crosscheck", "comparing (FLIP) and writing the pictures"):
        comparison = metrics.compare(peer_image, tracer_image)
        images.write_png(out / "tracer.png", tracer_image)
        images.write_png(out / f"{peer}.png", peer_image)
        images.write_png(out / "heatmap.png", metrics.heat_map(peer_image, tracer_image))
        images.write_png(out / "side_by_side.png", metrics.side_by_side(peer_image, tracer_image, peer_name, "tracer"))
    failed = failures(comparison, args)
    report = {
        "scene": str(args.scene),
        "width": scene["render"]["width"],
        "height": scene["render"]["height"],
        "samples": scene["render"]["samples"],
        "peer": peer,
        **peer_times,
        **comparison.as_dict(),
        "failed": failed,
        "output": str(out),
    }
    (out / "report.json").write_text(json.dumps(report, indent=2) + "\n")
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print(
            f"{args.scene}: tracer vs {peer_name} at {render['width']}x{render['height']}, "
            f"{render['samples']} spp\n{comparison.summary()}\nimages: {out}"
        )
        print("FAIL: " + "; ".join(failed) if failed else "ok: within the thresholds")
    return 1 if failed else 0


def main(argv: list[str] | None = None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    return run_reporting_errors("crosscheck", lambda: crosscheck(args))


if __name__ == "__main__":
    sys.exit(main())
