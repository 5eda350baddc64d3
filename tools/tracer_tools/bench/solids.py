"""Issue 55's cost targets for solids (CSG), side by side on this machine (2 threads):

1. a die (a box minus its 21 pips, spheres) against the box alone, the same scene otherwise:
   render times alternated A B A B, the median of the per-pair ratios (target <= 3);
2. the die against POV-Ray 3.7's CSG: tracer's render time over POV-Ray's reported trace time,
   alternated (target: at least 3x faster, a ratio <= 0.333);
3. 10^4 dice in a 100 x 100 grid against 16 (4 x 4), framed alike: the render time per ray
   traced, alternated (target: at most 2x);
4. with no target, the cost of a closed mesh in a solid: the Stanford bunny (3,674 triangles)
   minus a sphere against the bunny alone, and against POV-Ray's trace of the same.

    tools/bench solids [--pairs 7]

The report goes to standard output, as committed in docs/bench/bench-solids.md.
"""

import pathlib
import re
import tempfile

from tracer_tools.bench.common import alternated, targets_main
from tracer_tools.bench.versus import THREADS, tracer_render_seconds, tracer_summary_line, versus_povray

LIGHTS = """light {{ position ({x}, {y}, {z}) color 0.7 }}
light {{ position ({x2}, {y2}, {z2}) color 0.35 }}
material ivory {{ ka 0.1 kd (0.92, 0.9, 0.82) ks 0.5 n 60 }}
material ink   {{ ka 0.05 kd (0.08, 0.08, 0.1) ks 0.3 n 30 }}
plane {{ point (0, -1, 0) normal (0, 1, 0) material {{ ka 0.1 kd 0.5 km 0.25 }} }}
"""

# A die at (x, z): a box minus 21 spheres, one to six on its faces.
DIE = """let d = 0.5
fn pip(p) { sphere { center p radius 0.17 material ink } }
fn die(x, z) {
  difference { translate (x, 0, z)
    box { min (-1, -1, -1) max (1, 1, 1) material ivory }
    pip((0, 0, 1.08))
    for s in [-1, 1] { pip((1.08, s * d, s * d)) }
    for s in [-1, 0, 1] { pip((s * d, 1.08, -s * d)) }
    for s in [-1, 1] { for t in [-1, 1] { pip((-1.08, s * d, t * d)) } }
    for s in [-1, 1] { for t in [-1, 1] { pip((s * d, -1.08, t * d)) } }
    pip((0, -1.08, 0))
    for s in [-1, 1] { for t in [-1, 0, 1] { pip((s * d, t * d, -1.08)) } }
  }
}
"""


def one_die(folder: pathlib.Path) -> tuple[pathlib.Path, pathlib.Path]:
    """The die and the box alone (with the unused pip material, so both scenes hold the same)."""
    head = "render { width 1200 height 800 }\ncamera { eye (3.2, 3.4, 4.6) lookat (0, 0, 0) fovy 36 }\n"
    head += LIGHTS.format(x=5, y=9, z=7, x2=-6, y2=4, z2=3)
    die, box = folder / "die.scn", folder / "box.scn"
    die.write_text(head + DIE + "die(0, 0)\n")
    box.write_text(head + "box { min (-1, -1, -1) max (1, 1, 1) material ivory }\n")
    return die, box


def dice_grid(folder: pathlib.Path, side: int) -> pathlib.Path:
    """side x side dice 3 apart, seen from above at an angle that frames the grid alike at any side."""
    span = 3 * side
    head = (
        "render { width 800 height 600 }\n"
        f"camera {{ eye ({span * 0.5}, {span * 0.9}, {span * 1.3}) "
        f"lookat ({span * 0.5}, 0, {span * 0.45}) fovy 40 }}\n"
    )
    head += LIGHTS.format(x=span, y=2 * span, z=1.5 * span, x2=-0.5 * span, y2=span, z2=0.5 * span)
    scene = folder / f"dice{side}.scn"
    scene.write_text(head + DIE + f"for i in 0..{side} {{ for j in 0..{side} {{ die(3 * i + 1, 3 * j + 1) }} }}\n")
    return scene


BUNNY = pathlib.Path(__file__).resolve().parents[3] / "scenes" / "meshes" / "bunny.obj"


def bitten_bunny(folder: pathlib.Path) -> tuple[pathlib.Path, pathlib.Path]:
    """The bunny minus a sphere, and the bunny alone (as scenes/solids/carved.scn's left one)."""
    head = "render { width 1200 height 800 }\ncamera { eye (0, 2.4, 5.5) lookat (0, 0.9, 0) fovy 38 }\n"
    head += LIGHTS.format(x=4, y=9, z=6, x2=-6, y2=5, z2=4)
    bunny = f'mesh {{ file "{BUNNY}" scale 0.2 rotate {{ axis (0, 1, 0) angle 20 }} material ivory }}'
    bitten, whole = folder / "bitten.scn", folder / "bunny.scn"
    bitten.write_text(
        head + f"difference {{\n  {bunny}\n  sphere {{ center (0.7, 1.4, 0.5) radius 0.55 material ink }}\n}}\n"
    )
    whole.write_text(head + bunny + "\n")
    return bitten, whole


def seconds_per_mray(scene: pathlib.Path, folder: pathlib.Path) -> float:
    """The render time per million rays traced (the summary line's)."""
    line = tracer_summary_line(scene, folder)
    seconds = float(re.search(r", ([0-9.]+) s, ", line).group(1))
    mrays = float(re.search(r", ([0-9.]+) Mrays \(", line).group(1))
    return seconds / mrays


def main() -> int:
    args = targets_main("solids", __doc__, THREADS)
    with tempfile.TemporaryDirectory() as name:
        folder = pathlib.Path(name)
        die, box = one_die(folder)
        cost = alternated(
            lambda: tracer_render_seconds(die, folder), lambda: tracer_render_seconds(box, folder), args.pairs
        )
        print("| target | measured | met |\n|---|---|---|")
        print(
            f"| a die (a box minus 21 spheres) <= 3x the box alone | {cost['ratio']:.2f}x ({cost['a']:.3f} s "
            f"against {cost['b']:.3f} s at 1200 x 800; pairs {', '.join(f'{r:.2f}' for r in cost['ratios'])}) "
            f"| {'yes' if cost['ratio'] <= 3 else 'no'} |",
            flush=True,
        )
        peer = versus_povray(die, args.pairs, folder)
        print(
            f"| the die >= 3x faster than POV-Ray's trace | {1 / peer['ratio']:.1f}x (tracer "
            f"{peer['tracer_s']:.3f} s, POV-Ray {peer['povray_s']:.3f} s; ratio {peer['ratio']:.3f}) "
            f"| {'yes' if peer['ratio'] <= 1 / 3 else 'no'} |",
            flush=True,
        )
        few, many = dice_grid(folder, 4), dice_grid(folder, 100)
        grid = alternated(lambda: seconds_per_mray(many, folder), lambda: seconds_per_mray(few, folder), args.pairs)
        print(
            f"| 10^4 dice: time per ray <= 2x that of 16 | {grid['ratio']:.2f}x ({grid['a'] * 1e3:.0f} ns against "
            f"{grid['b'] * 1e3:.0f} ns a ray) | {'yes' if grid['ratio'] <= 2 else 'no'} |",
            flush=True,
        )
        bitten, whole = bitten_bunny(folder)
        mesh = alternated(
            lambda: tracer_render_seconds(bitten, folder), lambda: tracer_render_seconds(whole, folder), args.pairs
        )
        peer = versus_povray(bitten, args.pairs, folder)
        print(
            f"| (no target) the bunny minus a sphere, against the bunny alone and POV-Ray | {mesh['ratio']:.2f}x "
            f"the bunny ({mesh['a']:.3f} s against {mesh['b']:.3f} s at 1200 x 800); {1 / peer['ratio']:.1f}x "
            f"faster than POV-Ray's trace ({peer['povray_s']:.3f} s) | - |"
        )
    return 0
