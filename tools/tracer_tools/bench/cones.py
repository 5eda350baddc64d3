"""tools/bench cones: the SPD's rings and tree with analytic cones against tessellated ones.

    tools/bench cones [--spd ../shared/spd/nff] [--pairs 7] [--threads 2]

Converts rings and tree with tools/nff2scn twice (tracer's `cone`, and `--cones mesh`: unit
frustums within 0.1 pixel of the true cone, placed as instances), and makes a third copy with
every cone removed (what no cone, however fast, can beat), then times tracer_bench's render of
each in turn, the order reversed every other round (`--pairs` rounds, 5 renders each, the
median), and writes docs/bench/bench-cones.md with the machine. Ray counts come from the same runs.
"""

import argparse
import statistics
import sys

from tracer_tools import ROOT, option_types
from tracer_tools.nff import nff2scn

from .common import DOCS, OUT, TRACER_BENCH, provenance, run_json

HEADER = (
    "| scene | analytic ms | tessellated ms | tessellated / analytic (min-max) | without cones ms "
    "| bound: tessellated / without | build ms (analytic / tessellated) | rays (analytic / tessellated) |\n"
    "|---|--:|--:|--:|--:|--:|--:|--:|"
)
MODES = ("analytic", "mesh", "none")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="tools/bench cones", description=__doc__.split("\n")[0])
    parser.add_argument(
        "--spd",
        type=option_types.existing_folder,
        default=ROOT.parent / "shared" / "spd" / "nff",
        help="the SPD's NFF files",
    )
    parser.add_argument("--pairs", type=option_types.whole_number(1, 1_000_000), default=7)
    parser.add_argument("--threads", type=option_types.whole_number(0, 4096), default=2)
    args = parser.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    rows = []
    for name in ("rings", "tree"):
        # Without cones: the analytic scene less its cone lines (next to it: the same meshes folder).
        scenes = {
            "analytic": OUT / f"{name}_analytic.scn",
            "mesh": OUT / f"{name}_mesh.scn",
            "none": OUT / f"{name}_analytic_without_cones.scn",
        }
        for mode in ("analytic", "mesh"):
            nff2scn.convert_file(f"{args.spd}/{name}.nff", scenes[mode], cones=mode)
        analytic_lines = scenes["analytic"].read_text().splitlines(keepends=True)
        scenes["none"].write_text("".join(line for line in analytic_lines if not line.startswith("cone {")))
        times = {mode: [] for mode in MODES}
        ratios, results = [], {}
        for pair in range(args.pairs):
            for mode in MODES if pair % 2 == 0 else reversed(MODES):
                command = [TRACER_BENCH, scenes[mode], "--threads", args.threads, "--runs", 5, "--json"]
                results[mode] = run_json(command)
                times[mode].append(results[mode]["render_ms_median"])
            ratios.append(times["mesh"][-1] / times["analytic"][-1])
            print(f"tools/bench cones: {name} round {pair + 1}: mesh / analytic {ratios[-1]:.3f}", file=sys.stderr)
        median = {mode: statistics.median(times[mode]) for mode in MODES}
        rows.append(
            f"| {name} | {median['analytic']:.1f} | {median['mesh']:.1f} "
            f"| {statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f}) | {median['none']:.1f} "
            f"| {median['mesh'] / median['none']:.2f} "
            f"| {results['analytic']['build_ms']:.1f} / {results['mesh']['build_ms']:.1f} "
            f"| {results['analytic']['rays']:,} / {results['mesh']['rays']:,} |"
        )
    facts = provenance()
    (DOCS / "bench-cones.md").write_text(
        f"""# Analytic cones against tessellated ones (SPD rings and tree)

Measured by `tools/bench cones` on {facts['date']} at {facts['commit']}: {facts['machine']};
{args.threads} render threads, {args.pairs} rounds of the three scenes in turn (A B C C B A ...), each a
median of 5 in-process renders (tracer_bench), 512 x 512, one ray per pixel centre.

{HEADER}
{chr(10).join(rows)}

The tessellated cones are instances of a unit frustum with enough sides that the outline is
within 0.1 pixel of the true cone (`tools/nff2scn --cones mesh`): each costs a ray's transform
into the frustum's coordinates and a small BVH, where an analytic cone costs one quadratic.

"Without cones" is the analytic scene with every cone removed: no cone however fast could make
the scene faster than that, so tessellated / without is the most any cone could gain over the
tessellated ones (without cones the rays meet other things, so the bound is close, not exact).
In tree most rays meet the floor and its shadow rays dominate, and its 4,095 spheres and seven
lights are most of the time: issue 33's 2x is out of reach there whatever the cones cost.

What the analytic cones do to be fast (src/accel/world.cpp, world_queries.inl): a long cone
leaning across the axes is cut along its axis into pieces for the top level, each with the box
of its stretch (rings: 2.5 pieces a cylinder; a ray entering any piece tests the whole cone,
once); and a ray leaving a cone or sphere outwards skips that object (it cannot meet it
again: the hard case `RoundShapesRaysLeavingThemNeverMeetThemAgain` re-hits none of 500,000).
"""
    )
    print(f"tools/bench cones: wrote {DOCS / 'bench-cones.md'}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
