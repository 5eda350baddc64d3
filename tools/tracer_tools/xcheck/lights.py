"""A scene's lights as the point lights they are made of (docs/guide/lights.md), for the
converters: a point light is itself; an area light is its samples1 x samples2 samples, spanning
its rectangle corner to corner (a disc light: mapped onto the inscribed disc by the concentric
map), each with its share of the colour. A sphere light's samples turn to face each point: it
has no fixed points (the converters refuse it)."""

from __future__ import annotations

import math

import numpy as np

from . import PeerCannotExpress


def refuse_moving_samples(light: dict) -> None:
    """Raises PeerCannotExpress if the light's samples are not fixed points (jittered, adaptive,
    or a sphere's disc turned to each point): no peer can be given them."""
    if light.get("jitter") or light.get("adaptive") or light.get("shape") == "sphere":
        raise PeerCannotExpress(
            "the scene has a jittered, adaptive or sphere area light, whose samples are tracer's own (a random place "
            "per point, corners trusted, or a disc turned to each point): compare its grid instead"
        )


def light_points(light: dict) -> list[tuple[list[float], list[float]]]:
    """The light (an entry of `tracer --dump-json`'s lights) as (position, colour) point lights;
    refuse_moving_samples first."""
    refuse_moving_samples(light)
    if "samples" not in light:
        return [(light["position"], light["color"])]
    n1, n2 = light["samples"]
    centre, edge1, edge2 = (np.array(light[k], dtype=np.float64) for k in ("position", "edge1", "edge2"))
    share = (np.array(light["color"], dtype=np.float64) * (1.0 / (n1 * n2))).tolist()
    disc = light.get("shape") == "disc"
    points = []
    for i in range(n1):
        for j in range(n2):
            a = i / (n1 - 1) - 0.5 if n1 > 1 else 0.0
            b = j / (n2 - 1) - 0.5 if n2 > 1 else 0.0
            if disc:
                a, b = (0.5 * c for c in concentric(2 * a, 2 * b))
            points.append(((centre + a * edge1 + b * edge2).tolist(), share))
    return points


def concentric(x: float, y: float) -> tuple[float, float]:
    """Shirley and Chiu's concentric map of the square [-1, 1]^2 onto the unit disc."""
    if x == 0 and y == 0:
        return 0.0, 0.0
    if abs(x) > abs(y):
        r, angle = x, math.pi / 4 * (y / x)
    else:
        r, angle = y, math.pi / 2 - math.pi / 4 * (x / y)
    return r * math.cos(angle), r * math.sin(angle)
