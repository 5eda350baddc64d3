"""Scene description (the JSON of `tracer --dump-json`) -> POV-Ray 3.7 SDL, and POV-Ray's image.

POV-Ray is the peer most users would pick instead of tracer and shares its model (point
lights, Phong, mirror and refraction rays); set up as below it gives the same pixels. The rules,
each where the two renderers' defaults differ:
- `#version 3.7`, `assumed_gamma 1.0`, File_Gamma=1.0 and 16-bit PNG output: linear values;
  no antialiasing, no radiosity; `max_trace_level` = max_depth + 1 (POV-Ray counts the eye ray);
  `adc_bailout 0` (no weight cut-off); `ambient_light 1`.
- the camera by its vectors (location, direction, right, up: no look_at, so POV-Ray's
  left-handedness plays no part): the same rays through the pixel centres as tracer's.
- lights: point lights without fade; `shadowless` when the scene has `shadows false`.
- materials: POV-Ray multiplies ambient and diffuse by the pigment and by the opacity 1 - T, so
  the pigment is kd / (1 - T) with `transmit T`, `diffuse 1` and `ambient` ka / kd per channel (a
  channel with kd 0 gets a pigment of 1e-9, under any level); `phong` ks with `phong_size` n;
  `reflection` km; `interior { ior }`. POV-Ray's phong amount and transmit are one number each: a
  coloured ks, or a coloured kt on a surface with ka or kd, is written as its mean and reported
  (APPROXIMATED); clear glass (ka = kd = 0) takes any kt exactly, as a pigment of kt with filter 1.
- shadows through transmitting surfaces: POV-Ray always lets light through them, multiplied by
  T at each surface (tracer's `transparent_shadows true`); tracer's default opaque shadows differ
  there, and the report says so.
- patterns (ka, kd): checker, gradient, stripes (a stepped colour map) and rings (POV-Ray's wood
  without turbulence) in solid mapping, and images in planar mapping, each placed by a `matrix`
  (the inverse of the JSON's to_pattern); ka must be 0 or kd's pattern scaled per channel
  (POV-Ray's ambient multiplies the pigment). Spots, turbulence, marble and wood are refused
  (POV-Ray's noise is not Perlin's reference), as is mirrored image tiling; uv mapping is
  POV-Ray's uv_mapping on meshes, triangles and quads, written as mesh2 with tracer's (u, v)
  (`uv_vectors`), and refused on the other shapes (POV-Ray's own (u, v) of a sphere, a box, a
  cone or a disc are not tracer's).
- solids (CSG): POV-Ray's merge (tracer's union: no inner faces), intersection and difference,
  with spheres, boxes (placed by a `matrix`), closed cones and planes (half-spaces, the same
  side inside) as their parts; a union outside every other solid is no solid in the JSON (its
  shapes are listed as shapes: POV-Ray's union).
- shapes: spheres, planes, discs, cones and cylinders as POV-Ray's own (analytic); meshes as
  `mesh2` with tracer's placed corners and normals (xcheck.exact_meshes), each with an
  `inside_vector` (see _mesh2: without one POV-Ray may miss a mesh's farther faces); the flat
  shapes as triangles.
"""

from __future__ import annotations

import pathlib
import re
import shutil
import subprocess
from collections.abc import Sequence

import numpy as np

from . import ToolError, exact_meshes, mitsuba_textures
from .lights import light_points

TINY_PIGMENT = 1e-9  # a kd channel of 0 with ka above 0 (see the module's rules)


class PovrayMissing(ToolError):
    """The `povray` program is not installed."""

    exit_code = 4


def _v(values: Sequence[float]) -> str:
    return "<" + ", ".join(repr(float(v)) for v in values) + ">"


# What could not be written exactly, by material: printed once per conversion (APPROXIMATED).
APPROXIMATED: dict[str, str] = {}


def _grey(values: Sequence[float], what: str, material: dict) -> float:
    """One number for a colour POV-Ray takes as one: exact when grey, else the mean (noted)."""
    if values[0] == values[1] == values[2]:
        return float(values[0])
    name = material.get("name") or "(inline)"
    APPROXIMATED[f"{name} {what}"] = (
        f"material {name}: the coloured {what} {list(values)} is written as its mean (POV-Ray's is one number)"
    )
    return float(sum(values) / 3)


def _pov_matrix(to_pattern: Sequence[Sequence[float]]) -> str:
    """POV-Ray's `matrix` placing a pattern whose space is `to_pattern` (rows of 4) of the world:
    the inverse map, written as POV-Ray's rows (the images of x, y, z, then the origin)."""
    forward = np.array([*to_pattern, [0, 0, 0, 1]], dtype=np.float64)
    inverse = np.linalg.inv(forward)
    rows = [inverse[:3, column] for column in range(4)]
    return "matrix <" + ", ".join(repr(float(v)) for row in rows for v in row) + ">"


def _color_map(stops: list, stepped: bool) -> str:
    """A colour map; stepped (stripes): each stop's colour held up to the next stop."""
    entries = []
    for i, (at, colour) in enumerate(stops):
        if stepped and i > 0:
            entries.append(f"[{float(at)!r} rgb {_v(stops[i - 1][1])}]")
        entries.append(f"[{float(at)!r} rgb {_v(colour)}]")
    if stepped:
        entries.append(f"[1 rgb {_v(stops[-1][1])}]")
    return "color_map { " + " ".join(entries) + " }"


def _axis_turn(axis: Sequence[float], to: Sequence[float]) -> np.ndarray:
    """A rotation (3 x 3) taking unit `axis` onto unit `to` (POV-Ray's patterns run along fixed axes)."""
    a, b = np.array(axis, dtype=np.float64), np.array(to, dtype=np.float64)
    k, c = np.cross(a, b), float(np.dot(a, b))
    if c < -1 + 1e-12:  # opposite: a half turn about any axis across them
        other = np.array([1.0, 0, 0]) if abs(a[0]) < 0.9 else np.array([0, 1.0, 0])
        n = np.cross(a, other) / np.linalg.norm(np.cross(a, other))
        return 2 * np.outer(n, n) - np.eye(3)
    skew = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + skew + skew @ skew / (1 + c)


def pigment(
    paint: list | dict, factor: Sequence[float] = (1, 1, 1), outer: np.ndarray | None = None, has_uv: bool = False
) -> str:
    """A colour or a pattern (from the JSON) as POV-Ray's pigment, each colour times `factor`;
    `outer`: the enclosing pattern's world -> pattern map (4 x 4), which POV-Ray applies to a
    nested pigment before its own; `has_uv`: the shape is a mesh2 given tracer's (u, v) (so uv
    mapping is POV-Ray's uv_mapping). POV-Ray's own noise differs from Perlin's reference: spots,
    turbulence, marble and wood are refused (their definition is checked by tracer's unit tests
    instead)."""
    paint = mitsuba_textures.folded(paint, tuple(factor))
    if isinstance(paint, list):
        return f"pigment {{ rgb {_v(paint)} }}"
    kind, mapping = paint["pattern"], paint["mapping"]
    drawn = mapping == "solid" or (mapping == "planar" and kind == "image") or (mapping == "uv" and has_uv)
    if not drawn:
        where = " on a shape POV-Ray is not given tracer's (u, v) for" if mapping == "uv" else ""
        raise ToolError(f"a {kind} pattern with mapping {mapping}{where}: not written for POV-Ray")
    if mapping == "uv" and outer is not None:
        raise ToolError("a uv pattern inside another pattern: not written for POV-Ray")
    full = np.array([*paint["to_pattern"], [0, 0, 0, 1]], dtype=np.float64)
    to_pattern = full if outer is None else full @ np.linalg.inv(outer)  # from the outer pattern's space
    if kind == "checker":
        even, odd = pigment(paint["even"], outer=full, has_uv=has_uv), pigment(paint["odd"], outer=full, has_uv=has_uv)
        body = f"checker {even}, {odd}"
    elif kind in ("gradient", "stripes", "rings"):
        # Turned so that the pattern's axis is POV-Ray's: x for a gradient, z for wood's rings.
        to = (1, 0, 0) if kind != "rings" else (0, 0, 1)
        turn = np.eye(4)
        turn[:3, :3] = _axis_turn(paint["axis"], to)
        to_pattern = turn @ to_pattern
        stops = paint["colors"]
        # POV-Ray's wood has a triangle wave by default; tracer's rings rise and jump (a ramp).
        pattern = "gradient x" if kind != "rings" else "wood ramp_wave"
        body = pattern + " " + _color_map(stops, kind == "stripes")
    elif kind == "image":
        if "multiply" in paint:
            raise ToolError("an image pattern scaled for the ambient term: not written for POV-Ray")
        interpolate = "interpolate 2"
        once = "" if paint["wrap"] == "repeat" else " once"
        if paint["wrap"] == "mirror":
            raise ToolError("an image with wrap mirror: POV-Ray's image_map has no mirrored tiling")
        body = f'image_map {{ png "{paint["file"]}" gamma srgb map_type 0 {interpolate}{once} }}'
    else:
        raise ToolError(f"a {kind} pattern: POV-Ray's noise is not Perlin's reference, so it is not cross-checked")
    uv_mapping = "uv_mapping " if mapping == "uv" else ""
    return f"pigment {{ {uv_mapping}{body} {_pov_matrix(to_pattern[:3])} }}"


def _scaled_copy(ka: dict | list, kd: dict, ratio: list[float] | None = None) -> list[float] | None:
    """The per-channel factor s with ka = s kd for two patterns of one shape, or None."""
    if isinstance(ka, list) or isinstance(kd, list):
        if not (isinstance(ka, list) and isinstance(kd, list)):
            return None
        out = list(ratio) if ratio is not None else [None, None, None]
        for channel, (a, d) in enumerate(zip(ka, kd, strict=True)):
            if d == 0:  # any factor fits a black channel, if ka's is black too
                if a != 0:
                    return None
                continue
            if out[channel] is not None and abs(a / d - out[channel]) > 1e-12 * max(1.0, abs(out[channel])):
                return None
            out[channel] = a / d
        return out
    if {k: v for k, v in ka.items() if k not in ("even", "odd", "colors")} != {
        k: v for k, v in kd.items() if k not in ("even", "odd", "colors")
    }:
        return None
    if ka["pattern"] == "checker":
        ratio = _scaled_copy(ka["even"], kd["even"], ratio)
        return None if ratio is None else _scaled_copy(ka["odd"], kd["odd"], ratio)
    for (at_a, colour_a), (at_d, colour_d) in zip(ka.get("colors", []), kd.get("colors", []), strict=False):
        if at_a != at_d:
            return None
        ratio = _scaled_copy(colour_a, colour_d, ratio)
        if ratio is None:
            return None
    return ratio


def _patterned_texture(material: dict, finish_parts: list[str], has_uv: bool) -> str:
    """A material whose ka or kd is a pattern: the pigment is kd's; POV-Ray's ambient multiplies
    it, so ka must be 0 or the same pattern scaled per channel (else refused)."""
    kd, ka = material["kd"], material["ka"]
    if any(material.get("kt", [0, 0, 0])):
        raise ToolError("a patterned material that transmits: not written for POV-Ray")
    if isinstance(kd, list):
        raise ToolError("a patterned ka on a plain kd: POV-Ray's ambient multiplies the pigment")
    ka, kd = mitsuba_textures.folded(ka), mitsuba_textures.folded(kd)
    ambient = [0.0, 0.0, 0.0] if isinstance(ka, list) and not any(ka) else _scaled_copy(ka, kd)
    if ambient is not None:
        ambient = [0.0 if f is None else f for f in ambient]
    if ambient is None:
        raise ToolError("ka is not kd's pattern scaled: POV-Ray's ambient multiplies the pigment")
    finish = " ".join([f"ambient rgb {_v(ambient)} diffuse 1 brilliance 1", *finish_parts])
    return f"texture {{ {pigment(kd, has_uv=has_uv)} finish {{ {finish} }} }}"


def texture(material: dict, has_uv: bool = False) -> str:
    """A material as POV-Ray's texture and interior (the rules in the module's docstring);
    `has_uv`: on a mesh2 given tracer's (u, v)."""
    kd, ka, kt_colour = material["kd"], material["ka"], material.get("kt", [0, 0, 0])
    ks = _grey(material.get("ks", [0, 0, 0]), "ks", material)
    finish_parts = []
    if ks > 0:
        finish_parts.append(f"phong {ks!r} phong_size {float(material['n'])!r}")
    if any(material["km"]):
        finish_parts.append(f"reflection {{ rgb {_v(material['km'])} }}")
    if isinstance(kd, dict) or isinstance(ka, dict):
        return _patterned_texture(material, finish_parts, has_uv)
    if not any(kd) and not any(ka) and any(kt_colour):
        # Clear glass: the pigment is free, so a coloured kt is exact as a filter of 1.
        finish = " ".join(["ambient 0 diffuse 0", *finish_parts])
        filtered = ", ".join(repr(float(t)) for t in kt_colour)
        text = f"texture {{ pigment {{ rgbf <{filtered}, 1> }} finish {{ {finish} }} }}"
        return text + f" interior {{ ior {float(material['ior'])!r} }}"
    kt = _grey(kt_colour, "kt", material)
    if kt >= 1:
        raise ToolError("a kt of 1 or more: POV-Ray's transmit T scales diffuse and ambient by 1 - T")
    pigment = [max(d, TINY_PIGMENT if a > 0 else 0.0) for d, a in zip(kd, ka, strict=True)]
    ambient = [a / p if p > 0 else 0.0 for a, p in zip(ka, pigment, strict=True)]
    finish = " ".join([f"ambient rgb {_v(ambient)} diffuse 1 brilliance 1", *finish_parts])
    opacity = 1.0 - kt
    text = (
        f"texture {{ pigment {{ rgbt <{', '.join(repr(p / opacity) for p in pigment)}, {kt!r}> }} "
        f"finish {{ {finish} }} }}"
    )
    if kt > 0:
        text += f" interior {{ ior {float(material['ior'])!r} }}"
    return text


def _camera(scene: dict) -> str:
    """tracer's pinhole camera (src/render/camera.cpp) by its vectors."""
    camera, render = scene["camera"], scene["render"]
    eye, lookat, up = (np.array(camera[k], dtype=np.float64) for k in ("eye", "lookat", "up"))
    w = (eye - lookat) / np.linalg.norm(eye - lookat)
    u = np.cross(up, w)
    u /= np.linalg.norm(u)
    v = np.cross(w, u)
    height = 2 * np.tan(np.radians(camera["fovy"]) / 2)
    width = height * render["width"] / render["height"]
    return f"camera {{ perspective location {_v(eye)} direction {_v(-w)} right {_v(u * width)} up {_v(v * height)} }}"


def _mesh2(corners: np.ndarray, normals: np.ndarray, material: dict, uvs: np.ndarray | None = None) -> str:
    """Triangles (t, 3, 3) with their corner normals (zero: flat) and (u, v) (t, 3, 2) as one mesh2."""
    count = len(corners)
    if count == 0:
        return ""
    lines = ["mesh2 {", f"  vertex_vectors {{ {3 * count},"]
    lines += ["    " + ", ".join(_v(p) for p in triangle) for triangle in corners]
    lines.append("  }")
    smooth = bool(np.any(normals))
    if smooth:
        faces = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        missing = ~np.any(normals, axis=2)  # a corner without a normal takes its face's
        normals = np.where(missing[:, :, None], faces[:, None, :], normals)
        lines.append(f"  normal_vectors {{ {3 * count},")
        lines += ["    " + ", ".join(_v(n) for n in triangle) for triangle in normals]
        lines.append("  }")
    if uvs is not None:
        lines.append(f"  uv_vectors {{ {3 * count},")
        lines += ["    " + ", ".join(_v(uv) for uv in triangle) for triangle in uvs]
        lines.append("  }")
    indices = [f"    <{3 * t}, {3 * t + 1}, {3 * t + 2}>" for t in range(count)]
    lines += [f"  face_indices {{ {count},", *indices, "  }"]
    if uvs is not None:
        lines += [f"  uv_indices {{ {count},", *indices, "  }"]
    # Every mesh a solid: refraction needs an inside, and without one POV-Ray's search of the
    # mesh stops at the first hit it finds, even one the ray then ignores as nearer than its
    # tolerance, hiding the mesh's farther faces (shadow rays from a tooth's root passed
    # through the next tooth: 0.14% of SPD gears' pixels).
    lines.append("  inside_vector <0, 0, 1>")
    lines.append(f"  {texture(material, has_uv=uvs is not None)}\n}}")
    return "\n".join(lines)


def _flat_triangles(scene: dict) -> list[tuple[np.ndarray, dict, np.ndarray | None]]:
    """Each flat shape as placed triangles (t, 3, 3) with its material and, for a triangle or
    a quad, the corners' (u, v) (t, 3, 2) as docs/guide/patterns.md gives them."""
    out = []
    for kind in ("triangles", "quads", "boxes"):
        for shape in scene.get(kind, []):
            if kind == "triangles":
                local = [[shape["a"], shape["b"], shape["c"]]]
                uvs = [[(0, 0), (1, 0), (0, 1)]]
            elif kind == "quads":
                c, e1, e2 = (np.array(shape[k], dtype=np.float64) for k in ("corner", "edge1", "edge2"))
                local = [[c, c + e1, c + e1 + e2], [c, c + e1 + e2, c + e2]]
                uvs = [[(0, 0), (1, 0), (1, 1)], [(0, 0), (1, 1), (0, 1)]]
            else:
                lo, hi = np.array(shape["min"], dtype=np.float64), np.array(shape["max"], dtype=np.float64)
                p = [np.where([i & 1, i & 2, i & 4], hi, lo) for i in range(8)]
                quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
                local = [t for a, b, c, d in quads for t in ([p[a], p[b], p[c]], [p[a], p[c], p[d]])]
                uvs = None  # a box's faces' (u, v) are not written
            linear, translate = exact_meshes.placement(shape)
            placed = np.array(local, dtype=np.float64) @ linear.T + translate
            out.append((placed, shape["material"], None if uvs is None else np.array(uvs, dtype=np.float64)))
    return out


INTERIOR = re.compile(r" interior \{ ior ([^ ]+) \}")


def _solid_part(part: dict, iors: set[float]) -> str:
    """One shape of a solid, in POV-Ray's words (its texture after its placement: the JSON's
    patterns are placed in world coordinates), without an interior: its ior joins `iors`."""
    kind = part["kind"]
    shape = part[kind]
    if kind == "mesh":  # its inside_vector gives POV-Ray its inside
        linear, translate = exact_meshes.placement(shape)
        corners, normals, uvs = exact_meshes._triangles(
            shape["file"], linear, translate, shape.get("shading") != "flat"
        )
        text = _mesh2(corners, normals, shape["material"], uvs)
        iors.update(float(ior) for ior in INTERIOR.findall(text))
        return INTERIOR.sub("", text)
    material = texture(shape["material"])
    iors.update(float(ior) for ior in INTERIOR.findall(material))
    material = INTERIOR.sub("", material)
    if kind == "sphere":
        return f"sphere {{ {_v(shape['center'])}, {float(shape['radius'])!r} {material} }}"
    if kind == "cone":
        return (
            f"cone {{ {_v(shape['base'])}, {float(shape['base_radius'])!r}, {_v(shape['top'])}, "
            f"{float(shape['top_radius'])!r} {material} }}"
        )
    if kind == "half_space":
        distance = float(np.dot(shape["point"], shape["normal"]))
        return f"plane {{ {_v(shape['normal'])}, {distance!r} {material} }}"
    linear, translate = exact_meshes.placement(shape)
    rows = [*linear.T.ravel(), *translate]  # POV-Ray's matrix maps row vectors: p M
    matrix = ", ".join(repr(float(x)) for x in rows)
    return f"box {{ {_v(shape['min'])}, {_v(shape['max'])} matrix <{matrix}> {material} }}"


def _solid(solids: list, root: int) -> str:
    """A solid and the solids nested in it, written without recursion (they may nest deeply).
    Its interior (the ior of its parts that transmit) is the solid's: POV-Ray tracks the
    interiors a ray is in by object, and a ray entering one part of a lens and leaving by
    another would otherwise refract as if entering the second; tracer's faces each separate
    their material from air, which is one interior for the whole solid."""
    words = {"union": "merge", "intersection": "intersection", "difference": "difference"}
    iors: set[float] = set()
    out: list[str] = []
    stack: list[tuple[int, int]] = [(root, 0)]
    out.append(words[solids[root]["op"]] + " {")
    while stack:
        index, next_part = stack.pop()
        parts = solids[index]["parts"]
        if next_part == len(parts):
            out.append("}")
            continue
        stack.append((index, next_part + 1))
        part = parts[next_part]
        if part["kind"] == "solid":
            stack.append((part["solid"], 0))
            out.append(words[solids[part["solid"]]["op"]] + " {")
        else:
            out.append(_solid_part(part, iors))
    if len(iors) > 1:
        raise ToolError(
            f"a solid whose parts refract with different ior ({', '.join(map(str, sorted(iors)))}): "
            "POV-Ray's interior is the whole solid's"
        )
    if iors:
        out.insert(len(out) - 1, f"interior {{ ior {iors.pop()!r} }}")
    return "\n".join(out)


def _light_source(scene: dict, light: dict, shadowless: str, native_area_lights: bool) -> str:
    """POV-Ray's light_source blocks for one light: an area light's samples each a point light;
    a spotlight with POV-Ray's own formula (the same as tracer's); a parallel light from far
    beyond the scene (POV-Ray's shadows it only by what lies between its position's plane and the
    point: 10^4 times the camera's distance from the origin is beyond every committed scene);
    fading with POV-Ray's fade_distance and fade_power (the same formula). With
    `native_area_lights`, an area light is POV-Ray's area_light of the same grid."""
    fade = ""
    if "fade_distance" in light:
        fade = f" fade_distance {float(light['fade_distance'])!r} fade_power {float(light['fade_power'])!r}"
    kind = light.get("kind")
    if kind == "spot":
        at = np.array(light["position"], dtype=np.float64) + np.array(light["direction"], dtype=np.float64)
        return (
            f"light_source {{ {_v(light['position'])} color rgb {_v(light['color'])} spotlight point_at {_v(at)} "
            f"radius {float(light['radius'])!r} falloff {float(light['falloff'])!r} "
            f"tightness {float(light['tightness'])!r}{fade}{shadowless} }}"
        )
    if kind == "parallel":
        reach = 1e4 * (1 + float(np.max(np.abs(scene["camera"]["eye"]))))
        direction = np.array(light["direction"], dtype=np.float64)
        return (
            f"light_source {{ {_v(-reach * direction)} color rgb {_v(light['color'])} parallel "
            f"point_at {_v((1 - reach) * direction)}{shadowless} }}"
        )
    if native_area_lights and "samples" in light:
        n1, n2 = light["samples"]
        sampling = (" jitter" if light.get("jitter") else "") + (" adaptive 2" if light.get("adaptive") else "")
        sampling += {"disc": " circular", "sphere": " circular orient"}.get(light.get("shape"), "")
        return (
            f"light_source {{ {_v(light['position'])} color rgb {_v(light['color'])} area_light "
            f"{_v(light['edge1'])}, {_v(light['edge2'])}, {n1}, {n2}{sampling}{fade}{shadowless} }}"
        )
    return "\n".join(
        f"light_source {{ {_v(position)} color rgb {_v(color)}{fade}{shadowless} }}"
        for position, color in light_points(light)
    )


def to_povray_sdl(scene: dict, native_area_lights: bool = False) -> str:
    """The POV-Ray 3.7 scene text for a scene description (a dict from `tracer --dump-json`);
    `native_area_lights`: as render_scene's."""
    APPROXIMATED.clear()
    render = scene["render"]
    out = [
        f"// From `tracer --dump-json {scene['source']}` by tools/tracer_tools/xcheck/povray.py.",
        "#version 3.7;",
        "global_settings { assumed_gamma 1.0 max_trace_level "
        f"{render['max_depth'] + 1} adc_bailout 0 ambient_light rgb <1, 1, 1> }}",
        f"background {{ rgb {_v(render['background'])} }}",
        _camera(scene),
    ]
    shadowless = "" if render["shadows"] else " shadowless"
    # An area light as its samples, each a point light: POV-Ray's own area_light shades with the
    # whole light's illumination times the fraction of samples unblocked (measured: 3% darker in
    # a penumbra than the sum of the unblocked samples' shading, tracer's model).
    out += [_light_source(scene, light, shadowless, native_area_lights) for light in scene["lights"]]
    for sphere in scene["spheres"]:
        out.append(f"sphere {{ {_v(sphere['center'])}, {float(sphere['radius'])!r} {texture(sphere['material'])} }}")
    for plane in scene["planes"]:
        distance = float(np.dot(plane["point"], plane["normal"]))
        out.append(f"plane {{ {_v(plane['normal'])}, {distance!r} {texture(plane['material'])} }}")
    for disc in scene.get("discs", []):
        out.append(
            f"disc {{ {_v(disc['center'])}, {_v(disc['normal'])}, {float(disc['radius'])!r} "
            f"{texture(disc['material'])} }}"
        )
    for cone in scene.get("cones", []):
        is_open = "" if cone["caps"] else " open"
        out.append(
            f"cone {{ {_v(cone['base'])}, {float(cone['base_radius'])!r}, {_v(cone['top'])}, "
            f"{float(cone['top_radius'])!r}{is_open} {texture(cone['material'])} }}"
        )
    for mesh in scene["meshes"]:
        linear, translate = exact_meshes.placement(mesh)
        corners, normals, uvs = exact_meshes._triangles(mesh["file"], linear, translate, mesh.get("shading") != "flat")
        out.append(_mesh2(corners, normals, mesh["material"], uvs))
    for corners, material, uvs in _flat_triangles(scene):
        out.append(_mesh2(corners, np.zeros_like(corners), material, uvs))
    solids = scene.get("solids", [])
    out += [_solid(solids, index) for index, solid in enumerate(solids) if not solid["nested"]]
    return "\n".join(out) + "\n"


def render_scene(
    scene: dict,
    folder: pathlib.Path,
    threads: int = 2,
    antialias: tuple[float, int] | None = None,
    native_area_lights: bool = False,
) -> tuple[np.ndarray, dict]:
    """Renders the scene with POV-Ray into folder (scene.pov, povray.png); (the image as linear
    floats H x W x 3, POV-Ray's reported {"parse_seconds", "trace_seconds"}). `antialias`
    (threshold, depth): POV-Ray's adaptive method 2 (+A +AM2 +R, its jitter left on); else none.
    `native_area_lights`: area lights as POV-Ray's own area_light (for timing: it shades them
    otherwise), else as their samples."""
    povray = shutil.which("povray")
    if povray is None:
        raise PovrayMissing(
            "POV-Ray is not installed (Debian's `povray` package; tools/bootstrap --python installs it)"
        )
    render = scene["render"]
    if render["samples"] != 1 or render.get("antialias", "uniform") != "uniform":
        raise ToolError(
            "POV-Ray's antialiasing is its own, not tracer's: compare at 1 sample (--samples 1, no --adaptive)"
        )
    folder = pathlib.Path(folder).resolve()  # POV-Ray runs in it: a relative path would move
    pov = folder / "scene.pov"
    pov.write_text(to_povray_sdl(scene, native_area_lights))
    png = folder / "povray.png"
    command = [
        povray, f"+I{pov}", f"+O{png}", f"+W{render['width']}", f"+H{render['height']}",
        *(["-A"] if antialias is None else [f"+A{antialias[0]}", "+AM2", f"+R{antialias[1]}"]),
        "+FN16", "File_Gamma=1.0", "-D", "-P", "+Q9", f"+WT{threads}", "-V",
    ]  # fmt: skip
    done = subprocess.run(command, capture_output=True, text=True, cwd=folder)
    if done.returncode != 0 or not png.is_file():
        tail = "\n".join(done.stderr.strip().splitlines()[-8:])
        raise ToolError(f"POV-Ray failed on {pov} (exit {done.returncode}):\n{tail}")
    return read_png16(png), {**render_times(done.stderr), "approximated": sorted(APPROXIMATED.values())}


def render_times(log: str) -> dict:
    """POV-Ray's own Parse Time and Trace Time (seconds) from its statistics on stderr."""
    times = {}
    for name, key in (("Parse Time", "parse_seconds"), ("Trace Time", "trace_seconds")):
        found = re.search(name + r":.*\(([\d.]+) seconds\)", log)
        if found:
            times[key] = float(found.group(1))
    return times


def read_png16(path: pathlib.Path) -> np.ndarray:
    """A 16-bit linear PNG as floats in [0, 1] (OpenImageIO)."""
    import OpenImageIO as oiio

    image = oiio.ImageInput.open(str(path))
    if image is None:
        raise ToolError(f"cannot read {path}: {oiio.geterror()}")
    try:
        pixels = image.read_image(0, 0, 0, 3, oiio.FLOAT)
    finally:
        image.close()
    return np.asarray(pixels, dtype=np.float32)
