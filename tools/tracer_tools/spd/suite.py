"""tools/spd: Eric Haines' Standard Procedural Databases through tracer, in one command.

    tools/spd [--source ../shared/spd/src] [--size N] [--scenes balls,gears,...]

builds upstream's generators from --source, generates the scenes (size factor --size, default
theirs), converts each with tools/nff2scn, renders it under upstream's testing procedure (rays
through the pixel corners, 2 x 2 averaged; ray tree depth 5), times parsing, building and
tracing, cross-checks it with Mitsuba 3 (tools/crosscheck, with a measurement of which pixels
are ill-conditioned), compares its speed with Embree's (compare_scene.py and embree_scene from
--bench), cross-checks it with POV-Ray 3.7 (opaque shadows, and transparent ones where
something transmits), and writes docs/spd.md with an image of each scene beside upstream's (--images).
Everything else goes to --out (default build/spd). Steps can be left out: --no-crosscheck,
--no-embree, --no-povray.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import sys

from tracer_tools import option_types
from tracer_tools.nff import nff2scn
from tracer_tools.scenes import edit

from . import report, steps

SHARED = steps.ROOT.parent / "shared"


def parse_arguments(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="tools/spd", description=__doc__.split("\n")[0])
    parser.add_argument(
        "--source", type=option_types.existing_folder, default=SHARED / "spd" / "src", help="the generators' C source"
    )
    parser.add_argument(
        "--images", type=option_types.existing_folder, default=SHARED / "spd" / "images", help="upstream's images"
    )
    parser.add_argument(
        "--bench", type=option_types.existing_path, default=SHARED / "bench" / "embree-whitted", help="Embree anchor"
    )
    parser.add_argument(
        "--size",
        type=option_types.whole_number(1, 16384),
        default=None,
        help="size factor (default: each generator's own)",
    )
    parser.add_argument(
        "--scenes",
        type=option_types.free_text,
        default=",".join(steps.SCENES),
        help="comma-separated (default: all seven)",
    )
    parser.add_argument(
        "--out", type=option_types.output_folder, default=steps.ROOT / "build" / "spd", help="working folder"
    )
    parser.add_argument(
        "--docs", type=option_types.output_path, default=steps.ROOT / "docs" / "spd.md", help="the report to write"
    )
    parser.add_argument("--threads", type=option_types.whole_number(0, 4096), default=2)
    parser.add_argument(
        "--runs", type=option_types.whole_number(1, 1_000_000), default=5, help="timed renders per measurement (median)"
    )
    parser.add_argument(
        "--pairs", type=option_types.whole_number(1, 1_000_000), default=5, help="tracer/Embree pairs (A B A B ...)"
    )
    parser.add_argument("--no-crosscheck", action="store_true")
    parser.add_argument("--no-embree", action="store_true")
    parser.add_argument("--no-povray", action="store_true")
    parser.add_argument("--report-only", action="store_true", help="rewrite --docs from --out's results.json")
    args = parser.parse_args(argv)
    args.scenes = [name.strip() for name in args.scenes.split(",") if name.strip()]
    unknown = sorted(set(args.scenes) - set(steps.SCENES))
    if unknown:
        parser.error(f"unknown scenes {', '.join(unknown)} (the seven: {', '.join(steps.SCENES)})")
    if not (args.source / "balls.c").is_file():
        parser.error(f"no SPD generator source in {args.source} (give --source)")
    return args


def transmits(scn: pathlib.Path) -> bool:
    """True if a material of the converted scene has a kt."""
    return any(" kt " in line for line in scn.read_text().splitlines() if line.startswith("material"))


def run_scene(name: str, args: argparse.Namespace, generators: pathlib.Path, embree: pathlib.Path | None) -> dict:
    """Every step for one scene; a dict of what was measured."""
    folder = args.out / name
    folder.mkdir(parents=True, exist_ok=True)
    nff = folder / f"{name}.nff"
    steps.log(f"{name}: generating, converting")
    steps.generate(generators, name, args.size, nff)
    result = {"scene": name, "nff_bytes": nff.stat().st_size}
    scn, corners = folder / f"{name}.scn", folder / f"{name}_corners.scn"
    result["convert"] = nff2scn.convert_file(nff, scn, corner_rays=False)
    nff2scn.convert_file(nff, corners, corner_rays=True)
    result["parse_seconds"] = steps.median_seconds([str(steps.tracer_path("tracer")), "--check", str(scn)], 3)

    steps.log(f"{name}: rendering under upstream's procedure")
    result["stats"] = steps.render_corner_rays(corners, folder / "tracer.png", folder / "stats.json", args.threads)
    spd_rules = folder / f"{name}_corners_spd_rules.scn"
    steps.with_spd_rules(corners, spd_rules)
    result["spd_rules_rays"] = steps.ray_counts(spd_rules, folder / "stats_spd_rules.json", args.threads)
    result["bench"] = steps.bench(corners, args.threads, args.runs)

    if not args.no_crosscheck:
        steps.log(f"{name}: cross-checking with Mitsuba 3")
        check_folder = folder / "crosscheck"
        result["crosscheck"] = steps.crosscheck(scn, check_folder)
        unstable = steps.unstable_pixels(scn, check_folder, relative=steps.MITSUBA_SPAWN_OFFSET, trials=16)
        result["conditioning"] = steps.agreement_on_stable_pixels(check_folder, unstable)
    if not args.no_povray:
        steps.log(f"{name}: cross-checking with POV-Ray 3.7")
        result["povray"] = steps.crosscheck(scn, folder / "povray", "povray")
        if transmits(scn):
            transparent = folder / f"{name}_transparent_shadows.scn"
            edit.with_render_key(scn, transparent, "transparent_shadows true")
            result["povray_transparent"] = steps.crosscheck(transparent, folder / "povray_transparent", "povray")
    if embree is not None:
        steps.log(f"{name}: timing against Embree")
        compared = scn
        if transmits(scn):
            compared = folder / f"{name}_no_refraction.scn"
            steps.without_refraction(scn, compared)
            result["embree_refraction_off"] = True
        result["embree"] = steps.compare_with_embree(
            args.bench, embree, compared, args.pairs, args.runs, folder / "embree.json"
        )
    return result


def main(argv: list[str] | None = None) -> int:
    args = parse_arguments(argv)
    if args.report_only:
        report.write(args, json.loads((args.out / "results.json").read_text()))
        return 0
    args.out.mkdir(parents=True, exist_ok=True)
    steps.log(f"building the generators from {args.source}")
    generators = args.out / "generators"
    steps.build_generators(args.source, generators)
    embree = None if args.no_embree else steps.build_embree(args.bench, args.out / "embree")
    results = [run_scene(name, args, generators, embree) for name in args.scenes]
    (args.out / "results.json").write_text(json.dumps(results, indent=1))
    report.write(args, results)
    steps.log(f"wrote {args.docs} and {args.out / 'results.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
