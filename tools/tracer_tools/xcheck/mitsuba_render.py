"""Renders a converted scene with Mitsuba 3 and the plugins of xcheck.plugins."""

from __future__ import annotations

import pathlib
import sys

from . import MitsubaMissing, convert, exact_meshes

VARIANT = "llvm_ad_rgb"  # vectorised on the CPU through LLVM; scalar_rgb would call Python per ray

try:
    import drjit as dr
    import mitsuba as mi
    import numpy as np

    mi.set_variant(VARIANT)
except (ImportError, AttributeError) as error:  # reported by the command-line tools
    raise MitsubaMissing(
        f"Mitsuba 3 is not usable in {sys.executable} ({error}); tools/bootstrap "
        "--python makes .venv from tools/requirements.txt"
    ) from error
from . import plugins  # noqa: E402  (needs the variant)

plugins.register()


def load(xml_path: pathlib.Path, scene: dict, **parameters: object) -> mi.Scene:
    """Loads the XML written for `scene` (the --dump-json dict), gives every mesh whose file
    normals tracer does not use area-weighted vertex normals, and hands the integrator the
    meshes in float64 (xcheck.exact_meshes). `parameters` set the XML's defaults (crop_y,
    crop_height)."""
    mitsuba_scene = mi.load_file(str(xml_path), optimize=False, **parameters)  # optimize would merge shapes
    integrator = mitsuba_scene.integrator()
    if isinstance(integrator, plugins.WhittedIntegrator):
        integrator.use_exact_meshes(mitsuba_scene, *exact_meshes.exact_meshes(scene, pathlib.Path(xml_path).parent))
    params = mi.traverse(mitsuba_scene)
    normals_used = {}  # by file: blocks that share one read it once
    for index, mesh in enumerate(scene["meshes"]):
        if mesh["file"] not in normals_used:
            normals_used[mesh["file"]] = exact_meshes.obj_normals_used(mesh["file"])
        if mesh.get("shading") == "flat" or normals_used[mesh["file"]]:
            continue
        positions = np.array(params[f"mesh{index}.vertex_positions"], dtype=np.float64).reshape(-1, 3)
        faces = np.array(params[f"mesh{index}.faces"]).reshape(-1, 3)
        normals = exact_meshes.area_weighted_normals(positions, faces)
        params[f"mesh{index}.vertex_normals"] = mi.Float(normals.astype(np.float32).ravel())
    params.update()
    return mitsuba_scene


def render(mitsuba_scene: mi.Scene, seed: int = 0) -> np.ndarray:
    """The image as a float32 H x W x 3 array (linear, unclamped, top row first)."""
    image = mi.render(mitsuba_scene, seed=seed)
    dr.eval(image)
    return np.array(image, dtype=np.float32)[:, :, :3]


# Samples per strip: about 1 GB of Dr.Jit arrays per strip for this scene size.
SAMPLES_PER_STRIP = 1 << 24


def render_scene(scene: dict, out_dir: pathlib.Path) -> np.ndarray:
    """Converts the scene description to out_dir/scene.xml (and the planes' OBJ files) and
    renders it (float image), in strips of rows when there are many samples."""
    xml_path = convert.write_mitsuba_scene(scene, out_dir)
    width, height, samples = (scene["render"][k] for k in ("width", "height", "samples"))
    rows = max(1, SAMPLES_PER_STRIP // (width * samples))
    if rows >= height:
        return render(load(xml_path, scene))
    strips = [
        render(load(xml_path, scene, crop_y=str(top), crop_height=str(min(rows, height - top))))
        for top in range(0, height, rows)
    ]
    return np.concatenate(strips, axis=0)
