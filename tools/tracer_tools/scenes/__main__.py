"""tools/make-scene NAME [ARGS...]: runs one scene or mesh generator; `tools/make-scene` alone lists them."""

import importlib
import sys

# name: (module of tracer_tools.scenes, what it makes)
GENERATORS = {
    "bunny-obj": ("bunny_obj", "scenes/meshes/bunny.obj from the npm package bunny 1.0.1"),
    "many-objects": ("many_objects", "scenes of N random spheres or N bunny instances (tools/bench many)"),
    "subdivide-obj": ("subdivide_obj", "an OBJ with each triangle split in four (the bunny's larger sizes)"),
}


def main() -> int:
    if len(sys.argv) < 2 or sys.argv[1] not in GENERATORS:
        print(
            "usage: tools/make-scene NAME [ARGS...]   (tools/make-scene NAME --help for its options)\n", file=sys.stderr
        )
        for name, (_, meaning) in GENERATORS.items():
            print(f"  {name:15} {meaning}", file=sys.stderr)
        return 0 if len(sys.argv) < 2 else 2
    name = sys.argv.pop(1)
    sys.argv[0] = f"tools/make-scene {name}"
    module = importlib.import_module(f"tracer_tools.scenes.{GENERATORS[name][0]}")
    return module.main() or 0


if __name__ == "__main__":
    sys.exit(main())
