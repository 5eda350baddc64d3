"""tools/bench NAME [ARGS...]: runs one benchmark; `tools/bench` alone lists them."""

import importlib
import sys

# name: (module of tracer_tools.bench, what it measures and where its report goes)
BENCHMARKS = {
    "task2": ("task2", "task2 rendered 9 times: median time and Mrays/s (docs/bench-task2.txt)"),
    "bvh": ("bvh", "the four accelerators on the bunny at five sizes, against Embree (docs/performance*)"),
    "many": ("many", "many spheres and bunny instances, against Embree (docs/many-objects*)"),
    "single-mesh": ("single_mesh", "single-mesh scenes against an older commit's build (docs/single-mesh.md)"),
    "robustness": ("robustness", "what the robust rules and float cost and buy (docs/speed-vs-error.md)"),
    "large-obj": ("large_obj", "a 2.5M-triangle OBJ read and rendered, and refusals (docs/large-obj.md)"),
    "farm": ("farm", "the render farm's overhead and scaling (docs/farm-bench.md)"),
    "farm-engines": ("farm_engines", "Dask against Ray for the farm's tasks (docs/farm-engines.txt)"),
    "builds": ("builds", "this tree against an earlier commit on the single-mesh and many-objects scenes"),
    "compare-builds": ("compare_builds", "two builds of trace_parts alternated: time per query"),
}


def main() -> int:
    if len(sys.argv) < 2 or sys.argv[1] not in BENCHMARKS:
        print("usage: tools/bench NAME [ARGS...]   (tools/bench NAME --help for its options)\n", file=sys.stderr)
        for name, (_, meaning) in BENCHMARKS.items():
            print(f"  {name:15} {meaning}", file=sys.stderr)
        return 0 if len(sys.argv) < 2 else 2
    name = sys.argv.pop(1)
    sys.argv[0] = f"tools/bench {name}"
    module = importlib.import_module(f"tracer_tools.bench.{BENCHMARKS[name][0]}")
    return module.main() or 0


if __name__ == "__main__":
    sys.exit(main())
