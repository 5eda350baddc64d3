"""tools/bench NAME [ARGS...]: runs one benchmark; `tools/bench` alone lists them."""

import sys

from tracer_tools import subcommands

# name: (module of tracer_tools.bench, what it measures and where its report goes)
BENCHMARKS = {
    "language": ("language", "the scene language against POV-Ray's parser (docs/bench/bench-language.md)"),
    "cones": ("cones", "SPD rings and tree, analytic cones against tessellated ones (docs/bench/bench-cones.md)"),
    "patterns": ("patterns", "issue 54's costs: checkered task2, a 4096^2 texture, Whitted against POV-Ray"),
    "lights": (
        "lights",
        "issue 56's costs: soft shadows against a point light and POV-Ray (docs/bench/bench-lights.md)",
    ),
    "soft-shadows": (
        "soft_shadows",
        "issue 56's speed against error: grid, jitter, adaptive (docs/bench/speed-vs-error-soft-shadows.md)",
    ),
    "animation": (
        "animation",
        "issue 57's targets: start-up, an orbit against POV-Ray, 240 frames, the farm (docs/bench/bench-animation.md)",
    ),
    "solids": ("solids", "issue 55's costs: a die against a box and POV-Ray, 10^4 dice (docs/bench/bench-solids.md)"),
    "python": (
        "python_module",
        "issue 58's targets: import time, a render against the command line's, memory (docs/bench/bench-python.md)",
    ),
    "playground": (
        "playground",
        "issue 59's targets: the browser's render, edit to preview, first image, size (docs/bench/bench-playground.md)",
    ),
    "task2": ("task2", "task2 rendered 9 times: median time and Mrays/s (docs/bench/bench-task2.txt)"),
    "bvh": ("bvh", "the four accelerators on the bunny at five sizes, against Embree (docs/bench/performance*)"),
    "many": ("many", "many spheres and bunny instances, against Embree (docs/bench/many-objects*)"),
    "single-mesh": ("single_mesh", "single-mesh scenes against an older commit's build (docs/bench/single-mesh.md)"),
    "robustness": ("robustness", "what the robust rules and float cost and buy (docs/bench/speed-vs-error.md)"),
    "large-obj": ("large_obj", "a 2.5M-triangle OBJ read and rendered, and refusals (docs/bench/large-obj.md)"),
    "farm": ("farm", "the render farm's overhead and scaling (docs/bench/farm-bench.md)"),
    "farm-plan": ("farm_plan", "10^5 farm jobs read and planned (docs/bench/farm-plan.md)"),
    "farm-engines": ("farm_engines", "Dask against Ray for the farm's tasks (docs/bench/farm-engines.txt)"),
    "builds": ("builds", "this tree against an earlier commit on the single-mesh and many-objects scenes"),
    "compare-builds": ("compare_builds", "two builds of trace_parts alternated: time per query"),
    "versus": ("versus", "issue 35's table: tracer against Embree (render, build) and POV-Ray (trace)"),
    "watch": ("watch", "tracer --watch: from a save to the preview and the full image (docs/bench/bench-watch.txt)"),
    "flat-shapes": (
        "flat_shapes",
        "issue 34's figure: 10^6 quads, triangles, boxes from a loop (docs/bench/bench-flat-shapes.md)",
    ),
    "interrupt": ("interrupt", "Ctrl-C latency at 1024^2 and 8192^2 in each sampling mode (docs/bench/interrupt.md)"),
    "adaptive": (
        "adaptive",
        "adaptive antialiasing against uniform and POV-Ray at matched error (docs/bench/speed-vs-error.md)",
    ),
}


def main() -> int:
    return subcommands.run("tools/bench", "tracer_tools.bench", BENCHMARKS)


if __name__ == "__main__":
    sys.exit(main())
