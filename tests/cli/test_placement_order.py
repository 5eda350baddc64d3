#!/usr/bin/env python3
"""Placement steps apply in the order written (issue 53): random chains of scale, rotate,
translate and transform steps on every kind of placed block, inside nested groups, against the
map composed independently here (Rodrigues' rotation, plain Python): where tracer's scene
description puts points (round shapes, planes, lights), or the map its steps compose to (meshes,
boxes, quads, triangles)."""

import argparse
import json
import math
import pathlib
import random
import subprocess
import sys
import tempfile
import unittest

TRACER = ""
MESH = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "meshes" / "tetrahedron.obj"


def rotation(axis, degrees):
    """The 3 x 3 rotation, counter-clockwise looking down `axis` (the right-hand rule)."""
    length = math.sqrt(sum(a * a for a in axis))
    x, y, z = (a / length for a in axis)
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    t = 1 - c
    return [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]


def apply(steps, point):
    """`point` taken through `steps` ([kind, value] each), first to last."""
    p = list(point)
    for kind, value in steps:
        if kind == "scale":
            p = [p[i] * value[i] for i in range(3)]
        elif kind == "rotate":
            m = rotation(*value)
            p = [sum(m[r][c] * p[c] for c in range(3)) for r in range(3)]
        else:
            p = [p[i] + value[i] for i in range(3)]
    return p


def written(steps):
    """The steps as scene text: a transform block around a run of them, now and then."""
    out, i = [], 0
    while i < len(steps):
        if len(steps) - i >= 2 and i % 3 == 1:
            out.append("transform { " + " ".join(text(s) for s in steps[i : i + 2]) + " }")
            i += 2
        else:
            out.append(text(steps[i]))
            i += 1
    return " ".join(out)


def text(step):
    kind, value = step
    if kind == "rotate":
        axis, degrees = value
        return f"rotate {{ axis ({axis[0]!r}, {axis[1]!r}, {axis[2]!r}) angle {degrees!r} }}"
    return f"{kind} ({value[0]!r}, {value[1]!r}, {value[2]!r})"


def random_steps(rng, uniform, count):
    steps = []
    for _ in range(count):
        kind = rng.choice(["scale", "rotate", "translate"])
        if kind == "scale":
            f = rng.choice([-1, 1]) * rng.uniform(0.5, 2)
            value = [f, f, f] if uniform else [rng.choice([-1, 1]) * rng.uniform(0.5, 2) for _ in range(3)]
        elif kind == "rotate":
            value = ([rng.uniform(-1, 1) for _ in range(3)], rng.uniform(-180, 180))
        else:
            value = [rng.uniform(-3, 3) for _ in range(3)]
        steps.append((kind, value))
    return steps


def dumped_steps(shape):
    """The steps tracer's scene description gives a mesh, box, quad or triangle."""
    if "transform" in shape:
        return [
            (kind, (v["axis"], v["angle"]) if kind == "rotate" else v)
            for step in shape["transform"]
            for kind, v in step.items()
        ]
    return [
        ("scale", shape["scale"]),
        ("rotate", (shape["rotate"]["axis"], shape["rotate"]["angle"])),
        ("translate", shape["translate"]),
    ]


class PlacementOrder(unittest.TestCase):
    def close(self, got, want, what):
        for g, w in zip(got, want, strict=True):
            self.assertAlmostEqual(g, w, delta=1e-9 * (1 + abs(w)), msg=f"{what}: {got} != {want}")

    def test_random_chains_in_nested_groups(self):
        rng = random.Random(53)
        # kind -> (block text before the placement, uniform scale only, the points to check)
        for trial in range(40):
            outer, inner = random_steps(rng, True, rng.randint(0, 3)), random_steps(rng, True, rng.randint(0, 3))
            shapes = {
                "sphere": ("center (0.5, -0.25, 1) radius 0.5", True),
                "cylinder": ("base (0, 0, 0) top (0, 1, 0.5) radius 0.3", True),
                "cone": ("base (0.2, 0, 0) top (0, 2, 0) base_radius 0.5", True),
                "disc": ("center (1, 0, 0) normal (0, 1, 0) radius 0.4", True),
                "box": ("min (0, 0, 0) max (1, 2, 3)", False),
                "quad": ("corner (0, 0, 0) edge1 (1, 0, 0) edge2 (0, 1, 0)", False),
                "triangle": ("a (0, 0, 0) b (1, 0, 0) c (0, 1, 0)", False),
                "mesh": (f'file "{MESH}"', False),
            }
            own = {kind: random_steps(rng, uniform, rng.randint(1, 4)) for kind, (_, uniform) in shapes.items()}
            body = "\n".join(
                f"{kind} {{ {keys} {written(own[kind])} material {{ kd 1 }} }}" for kind, (keys, _) in shapes.items()
            )
            body += "\nlight { position (1, 2, 3) }\nplane { point (0, 1, 0) normal (0, 0, 1) material { kd 1 } }"
            scene = (
                "camera { eye (0, 0, 40) lookat (0, 0, 0) }\n"
                f"group {{ {written(outer)}\n group {{ {written(inner)}\n{body}\n }}\n}}\n"
            )
            with tempfile.TemporaryDirectory() as folder:
                path = pathlib.Path(folder) / "chain.scn"
                path.write_text(scene)
                result = subprocess.run([TRACER, "--dump-json", path], capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stderr + scene)
            dump = json.loads(result.stdout)
            groups = inner + outer  # the inner group first, then the outer

            def placed(steps, p, groups=groups):
                return apply(groups, apply(steps, p))

            what = f"trial {trial}"
            self.close(dump["spheres"][0]["center"], placed(own["sphere"], [0.5, -0.25, 1]), what + " sphere")
            cyl = dump["cones"][0]
            self.close(cyl["base"], placed(own["cylinder"], [0, 0, 0]), what + " cylinder")
            self.close(cyl["top"], placed(own["cylinder"], [0, 1, 0.5]), what + " cylinder")
            self.close(dump["cones"][1]["top"], placed(own["cone"], [0, 2, 0]), what + " cone")
            self.close(dump["discs"][0]["center"], placed(own["disc"], [1, 0, 0]), what + " disc")
            self.close(dump["lights"][0]["position"], placed([], [1, 2, 3]), what + " light")
            self.close(dump["planes"][0]["point"], placed([], [0, 1, 0]), what + " plane")
            for kind, key in [("box", "boxes"), ("quad", "quads"), ("triangle", "triangles"), ("mesh", "meshes")]:
                steps = dumped_steps(dump[key][0])
                for p in ([0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.3, -2, 5]):
                    self.close(apply(steps, p), placed(own[kind], p), f"{what} {kind}")

    def test_translate_then_rotate_sets_objects_around_a_circle(self):
        # The trap: three plates, each moved out and then turned, land on three spots.
        scene = "camera { eye (0, 5, 10) lookat (0, 0, 0) }\n" + "".join(
            f"sphere {{ center (0, 0, 0) radius 0.2 translate (2, 0, 0) rotate {{ angle {a} }} material {{ kd 1 }} }}\n"
            for a in (0, 120, 240)
        )
        with tempfile.TemporaryDirectory() as folder:
            path = pathlib.Path(folder) / "plates.scn"
            path.write_text(scene)
            dump = json.loads(subprocess.run([TRACER, "--dump-json", path], capture_output=True, text=True).stdout)
        centres = [s["center"] for s in dump["spheres"]]
        for centre, angle in zip(centres, (0, 120, 240), strict=True):
            self.close(centre, [2 * math.cos(math.radians(angle)), 0, -2 * math.sin(math.radians(angle))], "plate")


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--tracer", required=True)
    args, rest = parser.parse_known_args()
    TRACER = str(pathlib.Path(args.tracer).resolve())
    unittest.main(argv=[sys.argv[0], *rest])
