"""Issue 56's cost targets for soft shadows, side by side on this machine (2 threads):

1. the lamp (scenes/lights/lamp.scn, an 8 x 8 area light over a table) against the same scene
   with a point light at the lamp's centre: render times alternated A B A B, the median of the
   per-pair ratios (target <= 8: the samples' shadow rays cost far less than 64 point lights');
2. the lamp against POV-Ray 3.7's trace of the same scene with its own 8 x 8 area_light
   (POV-Ray shades it as the whole light times the fraction unblocked, which costs one Phong
   term a point; tracer adds the 64 samples' terms): tracer's render time over POV-Ray's
   reported trace time, alternated (target <= 0.25);
3. with no target, the same two for the window-lit room (scenes/lights/window.scn: every point
   of the room in a penumbra of the window's edges and bars), and the shadow rays traced.

    tools/bench lights [--pairs 7]

The report goes to standard output, as committed in docs/bench/bench-lights.md.
"""

import pathlib
import re
import tempfile

from tracer_tools import ROOT
from tracer_tools.bench.common import alternated, targets_main
from tracer_tools.bench.versus import THREADS, tracer_render_seconds, tracer_summary_line

LIGHTS = ROOT / "scenes" / "lights"


def with_point_light(scene: pathlib.Path, folder: pathlib.Path) -> pathlib.Path:
    """The scene with each area light replaced by a point light at its centre, of its colour."""
    text = re.sub(
        r"^area_light \{ position (\([^)]*\)).* color ([0-9.]+) \}$",
        r"light { position \1 color \2 }",
        scene.read_text(),
        flags=re.MULTILINE,
    )
    out = folder / f"{scene.stem}_point.scn"
    out.write_text(text)
    return out


def povray_trace_seconds(scene: pathlib.Path, folder: pathlib.Path) -> float:
    """POV-Ray's reported trace time of the scene, its area lights POV-Ray's own."""
    from tracer_tools.xcheck import povray, tracer_cli

    return povray.render_scene(tracer_cli.dump_json(scene), folder, native_area_lights=True)[1]["trace_seconds"]


def shadow_rays(scene: pathlib.Path, folder: pathlib.Path) -> float:
    """Millions of shadow rays traced (the summary line's)."""
    return float(re.search(r", ([0-9.]+) M shadow", tracer_summary_line(scene, folder)).group(1))


def row(name: str, scene: pathlib.Path, folder: pathlib.Path, pairs: int, targets: bool) -> None:
    """The scene's two comparisons as table rows (with their targets, or without)."""
    point = with_point_light(scene, folder)
    own = alternated(lambda: tracer_render_seconds(scene, folder), lambda: tracer_render_seconds(point, folder), pairs)
    peer = alternated(lambda: tracer_render_seconds(scene, folder), lambda: povray_trace_seconds(scene, folder), pairs)
    rays = f"{shadow_rays(scene, folder):.2f} M shadow rays against {shadow_rays(point, folder):.2f} M"
    own_met = ("yes" if own["ratio"] <= 8 else "no") if targets else "-"
    peer_met = ("yes" if peer["ratio"] <= 0.25 else "no") if targets else "-"
    print(
        f"| {name}: 8 x 8 area light {'<= 8x' if targets else 'against'} a point light at its centre | "
        f"{own['ratio']:.2f}x ({own['a']:.3f} s against {own['b']:.3f} s at 640 x 480; {rays}; pairs "
        f"{', '.join(f'{r:.2f}' for r in own['ratios'])}) | {own_met} |",
        flush=True,
    )
    print(
        f"| {name}: {'<= 0.25x ' if targets else ''}POV-Ray's trace with its own 8 x 8 area_light | "
        f"{peer['ratio']:.3f}x (tracer {peer['a']:.3f} s, POV-Ray {peer['b']:.3f} s; pairs "
        f"{', '.join(f'{r:.3f}' for r in peer['ratios'])}) | {peer_met} |",
        flush=True,
    )


def main() -> int:
    args = targets_main("lights", __doc__, THREADS)
    with tempfile.TemporaryDirectory() as name:
        folder = pathlib.Path(name)
        print("| target | measured | met |\n|---|---|---|")
        row("the lamp", LIGHTS / "lamp.scn", folder, args.pairs, targets=True)
        row("(no target) the window", LIGHTS / "window.scn", folder, args.pairs, targets=False)
    return 0
