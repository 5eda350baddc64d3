"""tools/make-scene NAME [ARGS...]: runs one scene or mesh generator; `tools/make-scene` alone lists them."""

import sys

from tracer_tools import subcommands

# name: (module of tracer_tools.scenes, what it makes)
GENERATORS = {
    "bunny-obj": ("bunny_obj", "scenes/meshes/bunny.obj from the npm package bunny 1.0.1"),
    "many-objects": ("many_objects", "scenes of N random spheres or N bunny instances (tools/bench many)"),
    "subdivide-obj": ("subdivide_obj", "an OBJ with each triangle split in four (the bunny's larger sizes)"),
}


def main() -> int:
    return subcommands.run("tools/make-scene", "tracer_tools.scenes", GENERATORS)


if __name__ == "__main__":
    sys.exit(main())
