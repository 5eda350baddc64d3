"""tools/bench cones: the SPD's rings and tree with analytic cones against tessellated ones.

    tools/bench cones [--spd ../shared/spd/nff] [--pairs 7] [--threads 2]

Converts rings and tree with tools/nff2scn twice (tracer's `cone`, and `--cones mesh`: unit
frustums within 0.1 pixel of the true cone, placed as instances), then times tracer_bench's
render of each, alternating A B A B (`--pairs` pairs, 5 renders each, the median), and writes
docs/bench-cones.md with the machine. Ray counts come from the same runs.
"""

import argparse
import statistics
import sys

from tracer_tools import ROOT
from tracer_tools.nff import nff2scn

from .common import DOCS, OUT, TRACER_BENCH, provenance, run_json

HEADER = (
    "| scene | analytic ms | tessellated ms | tessellated / analytic (min-max) | build ms (analytic / tessellated) "
    "| rays (analytic / tessellated) |\n|---|--:|--:|--:|--:|--:|"
)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="tools/bench cones", description=__doc__.split("\n")[0])
    parser.add_argument("--spd", default=str(ROOT.parent / "shared" / "spd" / "nff"), help="the SPD's NFF files")
    parser.add_argument("--pairs", type=int, default=7)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    rows = []
    for name in ("rings", "tree"):
        scenes = {}
        for mode in ("analytic", "mesh"):
            scenes[mode] = OUT / f"{name}_{mode}.scn"
            nff2scn.convert_file(f"{args.spd}/{name}.nff", scenes[mode], cones=mode)
        times = {"analytic": [], "mesh": []}
        ratios, results = [], {}
        for pair in range(args.pairs):
            for mode in ("analytic", "mesh") if pair % 2 == 0 else ("mesh", "analytic"):
                command = [TRACER_BENCH, scenes[mode], "--threads", args.threads, "--runs", 5, "--json"]
                results[mode] = run_json(command)
                times[mode].append(results[mode]["render_ms_median"])
            ratios.append(times["mesh"][-1] / times["analytic"][-1])
            print(f"tools/bench cones: {name} pair {pair + 1}: mesh / analytic {ratios[-1]:.3f}", file=sys.stderr)
        rows.append(
            f"| {name} | {statistics.median(times['analytic']):.1f} | {statistics.median(times['mesh']):.1f} "
            f"| {statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f}) "
            f"| {results['analytic']['build_ms']:.1f} / {results['mesh']['build_ms']:.1f} "
            f"| {results['analytic']['rays']:,} / {results['mesh']['rays']:,} |"
        )
    facts = provenance()
    (DOCS / "bench-cones.md").write_text(
        f"""# Analytic cones against tessellated ones (SPD rings and tree)

Measured by `tools/bench cones` on {facts['date']} at {facts['commit']}: {facts['machine']};
{args.threads} render threads, {args.pairs} pairs alternated (A B B A ...), each a median of 5
in-process renders (tracer_bench), 512 x 512, one ray per pixel centre.

{HEADER}
{chr(10).join(rows)}

The tessellated cones are instances of a unit frustum with enough sides that the outline is
within 0.1 pixel of the true cone (`tools/nff2scn --cones mesh`): each costs a ray's transform
into the frustum's coordinates and a small BVH, where an analytic cone costs one quadratic. In
tree most rays meet the floor and its shadow rays dominate: the cones are a few percent of the
time either way.
"""
    )
    print(f"tools/bench cones: wrote {DOCS / 'bench-cones.md'}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
