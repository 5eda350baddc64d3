"""docs/spd.md from the suite's measurements: tables, and each image beside upstream's."""

from __future__ import annotations

import argparse
import datetime
import pathlib
import subprocess

from PIL import Image

from tracer_tools.xcheck import speed_vs_error

from . import steps

SIDE = 320  # pixels of each half of a side-by-side image

RULES = pathlib.Path(__file__).with_name("rules.md")  # the rule-by-rule section, as written by hand


def machine(measured_at: str) -> str:
    """The CPU, cores and OS, and the renderer's version: the last commit to src/ before the
    measurement (tools and docs do not change it)."""
    command = ["git", "log", "-1", "--format=%h", f"--before={int(measured_at)}", "--", "src"]
    commit = subprocess.run(command, capture_output=True, text=True, cwd=steps.ROOT)
    return f"{speed_vs_error.machine()}; tracer's src/ at {commit.stdout.strip()}"


def side_by_side(tracer_png: pathlib.Path, upstream_png: pathlib.Path, out_png: pathlib.Path) -> None:
    ours = Image.open(tracer_png).convert("RGB").resize((SIDE, SIDE), Image.LANCZOS)
    canvas = Image.new("RGB", (2 * SIDE, SIDE))
    canvas.paste(ours, (0, 0))
    if upstream_png.is_file():
        canvas.paste(Image.open(upstream_png).convert("RGB").resize((SIDE, SIDE), Image.LANCZOS), (SIDE, 0))
    canvas.save(out_png, optimize=True)


def _ms(seconds: float) -> str:
    return f"{seconds * 1000:,.1f}"


def primitives_table(results: list[dict]) -> str:
    lines = [
        "| scene | spheres | polygons (triangles) | cones (sides) | lights | NFF | convert | parse + check |",
        "|---|--:|--:|--:|--:|--:|--:|--:|",
    ]
    for r in results:
        c = r["convert"]
        sides = sorted(set(c["cone_sides"].values()))
        cones = f"{c['cones']:,} ({sides[0]}-{sides[-1]})" if sides else "0"
        lines.append(
            f"| {r['scene']} | {c['spheres']:,} | {c['polygons']:,} ({c['triangles']:,}) | {cones} | {c['lights']} "
            f"| {r['nff_bytes'] / 1e6:.2f} MB | {c['seconds']:.2f} s | {r['parse_seconds']:.2f} s |"
        )
    return "\n".join(lines)


def rays_table(results: list[dict]) -> str:
    lines = [
        "| scene | eye rays | eye rays that hit | reflection | refraction | shadow | total "
        "| build ms | trace ms | Mrays/s |",
        "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|",
    ]
    for r in results:
        rays, bench = r["stats"]["rays"], r["bench"]
        build = bench["build_ms"] / 1000
        trace = bench["render_ms_median"] / 1000
        lines.append(
            f"| {r['scene']} | {rays['primary']:,} | {rays['primary_hits']:,} | {rays['reflection']:,} "
            f"| {rays['refraction']:,} | {rays['shadow']:,} | {rays['total']:,} | {_ms(build)} | {_ms(trace)} "
            f"| {rays['total'] / trace / 1e6:.1f} |"
        )
    return "\n".join(lines)


# Upstream's published counts at the default size (its Readme.txt, "Database Analysis"): eye rays
# that hit, reflection, refraction and shadow rays, 513 x 513 eye rays, depth 5.
UPSTREAM_COUNTS = {
    "balls": (263169, 175095, 0, 954368),
    "gears": (245086, 304643, 207564, 2246955),
    "mount": (173125, 354769, 354769, 412922),
    "rings": (263169, 315236, 0, 1085002),
    "teapot": (161120, 225248, 0, 407656),
    "tetra": (49788, 0, 0, 46112),
    "tree": (169836, 0, 0, 1097419),
}


def _versus(ours: int, theirs: int) -> str:
    if theirs == 0:
        return f"{ours:,} (0)" if ours else "0"
    return f"{ours:,} ({100 * (ours - theirs) / theirs:+.2f}%)"


def upstream_rules_table(results: list[dict]) -> str:
    """Counts under `spawn_rules spd` against upstream's table; refraction also with the total
    internal reflections added (upstream's figure counts them)."""
    lines = [
        "| scene | eye rays that hit | reflection | refraction | refraction + TIR | shadow "
        "| upstream's (hit, refl., refr., shadow) |",
        "|---|--:|--:|--:|--:|--:|---|",
    ]
    for r in results:
        if "spd_rules_rays" not in r or r["scene"] not in UPSTREAM_COUNTS:
            continue
        rays, theirs = r["spd_rules_rays"], UPSTREAM_COUNTS[r["scene"]]
        tir = rays.get("total_internal_reflections", 0)
        lines.append(
            f"| {r['scene']} | {_versus(rays['primary_hits'], theirs[0])} | {_versus(rays['reflection'], theirs[1])} "
            f"| {_versus(rays['refraction'], theirs[2])} | {_versus(rays['refraction'] + tir, theirs[2])} "
            f"| {_versus(rays['shadow'], theirs[3])} | {', '.join(f'{n:,}' for n in theirs)} |"
        )
    return "\n".join(lines)


def crosscheck_table(results: list[dict]) -> str:
    lines = [
        "| scene | over 2 levels | px | ill-conditioned px | over 2 levels on the others | RMSE | FLIP |",
        "|---|--:|--:|--:|--:|--:|--:|",
    ]
    for r in results:
        if "crosscheck" not in r:
            continue
        x, c = r["crosscheck"], r["conditioning"]
        over = round(x["over_2"] * x["pixels"])
        lines.append(
            f"| {r['scene']} | {100 * x['over_2']:.3f}% | {over:,} | {c['unstable']:,} "
            f"| {100 * c['over_2_stable_share']:.3f}% ({c['over_2_stable']:,} px) | {x['rmse']:.5f} "
            f"| {x['flip_mean']:.5f} |"
        )
    return "\n".join(lines)


def povray_table(results: list[dict]) -> str:
    """tracer against POV-Ray 3.7: pixels apart, and the two trace times."""
    lines = [
        "| scene | shadows | over 2 levels | px | over 8 levels | largest | RMSE | POV-Ray trace s | tracer trace s |",
        "|---|---|--:|--:|--:|--:|--:|--:|--:|",
    ]
    for r in results:
        for key, shadows in (("povray", "opaque"), ("povray_transparent", "transparent")):
            if key not in r:
                continue
            x = r[key]
            over = round(x["over_2"] * x["pixels"])
            lines.append(
                f"| {r['scene']} | {shadows} | {100 * x['over_2']:.4f}% | {over:,} | {100 * x['over_8']:.4f}% "
                f"| {x['max_levels']} | {x['rmse']:.6f} | {x.get('trace_seconds', float('nan')):.3f} "
                f"| {r['bench']['render_ms_median'] / 1000:.3f} |"
            )
    return "\n".join(lines)


def embree_table(results: list[dict]) -> str:
    lines = [
        "| scene | tracer ms | Embree ms | tracer / Embree (min-max) | build tracer / Embree ms | note |",
        "|---|--:|--:|--:|--:|---|",
    ]
    for r in results:
        e = r.get("embree")
        if e is None:
            continue
        if "refused" in e:
            lines.append(f"| {r['scene']} | | | no ratio | | {e['refused']} |")
            continue
        note = "refraction off (embree_scene has none): kt removed in both" if r.get("embree_refraction_off") else ""
        lines.append(
            f"| {r['scene']} | {e['tracer_render_ms']:,.1f} | {e['embree_render_ms']:,.1f} "
            f"| {e['render_ratio']:.2f} ({e['render_ratio_min']:.2f}-{e['render_ratio_max']:.2f}) "
            f"| {e['tracer_build_ms']:,.1f} / {e['embree_build_ms']:,.1f} | {note} |"
        )
    return "\n".join(lines)


def write(args: argparse.Namespace, results: list[dict]) -> None:
    images = args.docs.parent / "spd"
    images.mkdir(parents=True, exist_ok=True)
    gallery = []
    for r in results:
        name = r["scene"]
        side_by_side(args.out / name / "tracer.png", args.images / f"{name}.png", images / f"{name}.png")
        gallery.append(f"**{name}**: tracer (left), upstream's POV-Ray render (right)\n\n![{name}](spd/{name}.png)\n")
    size = "default size" if args.size is None else f"size factor {args.size}"
    measured_at = (args.out / "results.json").stat().st_mtime
    measured = datetime.date.fromtimestamp(measured_at)
    text = f"""# The Standard Procedural Databases through tracer

Generated by `tools/spd` ({size}; measured {measured}) on {machine(measured_at)}; {args.threads} render threads.
Eric Haines' SPD (1987, CC0): seven generated scenes in NFF, made to compare Whitted ray tracers on
common ground. `tools/spd` builds upstream's generators, generates each scene, converts it with
`tools/nff2scn` (rules: `tools/tracer_tools/nff/convert.py`), renders it under upstream's procedure, cross-checks
it with Mitsuba 3 and times it against Embree. Raw figures: `build/spd/results.json` after a run.

{RULES.read_text()}
## Scenes, conversion and parsing

Conversion is `tools/nff2scn` (Python: reading, triangulating, tessellating, writing); parse + check
is the wall time of `tracer --check` on the converted scene (a process start included, the
OBJ files looked at but not read; median of 3).

{primitives_table(results)}

## Rays and times under upstream's procedure (513 x 513 eye rays, depth 5)

Counts from `tracer --stats-json`; build and trace times from `tracer_bench` (in-process, median
of {args.runs} renders, {args.threads} threads). Build is the BVHs (objects and meshes).
Reading the OBJ files is in neither column, nor in "parse + check" above (`--check` looks at
mesh files without reading them).

{rays_table(results)}

## Ray counts under upstream's rules against its published table

The same corner-ray renders with `spawn_rules spd` (upstream's rules 8 and 10 as it states them: a
reflection ray at every hit on a surface with km or kt above 0, whatever the weight; a shadow ray
wherever the normal faces the light, none elsewhere; no weight cut-off). The image is the same;
only rays of no weight are added. Differences from upstream's table in brackets.

{upstream_rules_table(results)}

Every count is within 0.4% of upstream's but gears' refraction: tracer spawns no refracted ray
under total internal reflection (rule 9), and upstream's figure matches tracer's refracted rays
plus its total internal reflections (`--stats-json`'s `total_internal_reflections`) to 0.01%: the
tracer that made the table counted a refraction ray at those hits too. The small remaining
differences come from rays that graze silhouettes and edges, which any two tracers decide
differently (upstream: "the numbers given can vary noticeably from a given ray tracer").

## Cross-check with Mitsuba 3 (512 x 512, 1 sample at each pixel centre)

`tools/crosscheck` renders the converted scene with tracer (double precision) and with Mitsuba 3
(the same Whitted integrator as plugins: docs/crosscheck.md). Chains of mirror reflections among
small spheres are chaotic: a float32 rounding of the first hit point becomes a different sphere
three bounces later (tracer's own float build, `-DTRACER_REAL=float`, differs from its double
build on balls by 0.36% of the pixels and on rings by 0.05%). So the integrator carries each
mirror chain in float64: the primary ray is tracer's own ray through the pixel centre, Mitsuba's
float32 search names the shape each ray meets next, and the hit point, normal and mirror
direction are worked out again in float64 (the sphere's centre and radius as the scene gives
them, a triangle's corners and normals as tracer reads and places them); only shadow rays,
refracted branches and the choice of shape on a grazing ray stay float32. To tell the pixels that float32 still decides,
tracer also renders each scene with the eye moved, in 16 random directions, by as much as the
plugins move every secondary ray off its surface (64 float32 ulps of the scene's size: 7.6e-6 of
the eye's distance from the origin); a pixel that changes by more than 2 levels under such a move
is ill-conditioned at float32's precision. The last columns count the disagreement on the other
pixels only.

{crosscheck_table(results)}

## Cross-check with POV-Ray 3.7 (512 x 512, 1 ray at each pixel centre)

`tools/crosscheck --with povray` converts the scene to POV-Ray's language (the rules:
`tools/tracer_tools/xcheck/povray.py`) and renders it with Debian's `povray` (no antialiasing,
linear 16-bit output, 2 threads). POV-Ray lets light through transmitting surfaces, multiplied by
their transmittance at each surface: tracer's `transparent_shadows true`. Under tracer's default
opaque shadows the scenes with glass (gears, mount) differ exactly there, in the shadows of the
glass; with transparent shadows they agree. Trace times: POV-Ray's own reported Trace Time for
that render (pixel centres, 512 x 512); tracer's the median of tracer_bench above (corner rays,
513 x 513).

{povray_table(results)}

## Speed against Embree (side by side, alternating, {args.threads} threads)

`compare_scene.py` with `embree_scene` (the Embree 3 anchor: the same Whitted model, spheres,
planes and meshes), {args.pairs} pairs, median of the per-pair ratios; the scene at 512 x 512 with
rays through the pixel centres. Ratios above 1: tracer is slower.

{embree_table(results)}

## Images

{chr(10).join(gallery)}"""
    args.docs.write_text(text)
