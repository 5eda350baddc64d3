"""The suite's steps, one function each: build, generate, convert, render, cross-check, compare."""

from __future__ import annotations

import json
import os
import pathlib
import re
import shutil
import statistics
import subprocess
import sys
import time

import numpy as np

from tracer_tools import ROOT
from tracer_tools.scenes.edit import with_render_key

SCENES = ("balls", "gears", "mount", "rings", "teapot", "tetra", "tree")
# How far the Mitsuba plugins move a ray's origin off a surface, relative to the scene's size:
# 64 float32 ulps (tools/tracer_tools/xcheck/plugins.py). Pixels that change when the eye moves this far
# are beyond what the float32 cross-check can confirm (unstable_pixels).
MITSUBA_SPAWN_OFFSET = 64 * 2.0**-23
GENERATOR_CC = "cc -O2 -w -std=gnu89 -include compat.h"  # as upstream's build.sh: 1980s C


def log(message: str) -> None:
    print(f"tools/spd: {message}", file=sys.stderr, flush=True)


def ensure_debian_packages(packages: list[str]) -> None:
    """Installs the Debian packages that are missing (as tools/bootstrap does)."""
    missing = [
        package
        for package in packages
        if "install ok installed"
        not in subprocess.run(["dpkg-query", "-W", "-f=${Status}", package], capture_output=True, text=True).stdout
    ]
    if not missing:
        return
    log(f"installing {' '.join(missing)}")
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    subprocess.run([*sudo, "apt-get", "update", "-qq"], check=True)
    environment = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    subprocess.run(
        [*sudo, "apt-get", "install", "-y", "-qq", "--no-install-recommends", *missing],
        check=True,
        env=environment,
        stdout=subprocess.DEVNULL,
    )


def build_generators(source: pathlib.Path, folder: pathlib.Path) -> None:
    """Compiles upstream's generators from `source` (their C files, compat.h and makefile) into folder."""
    ensure_debian_packages(["make", "gcc"])
    folder.mkdir(parents=True, exist_ok=True)
    for path in source.iterdir():
        if path.suffix in (".c", ".h") or path.name == "makefile":
            shutil.copy2(path, folder / path.name)
    subprocess.run(["make", "-s", "-C", str(folder), f"CC={GENERATOR_CC}", *SCENES], check=True, stdout=sys.stderr)


def generate(generators: pathlib.Path, scene: str, size: int | None, nff_path: pathlib.Path) -> None:
    """Runs one generator (size factor `size`, None for its default) into nff_path."""
    command = [str(generators / scene)] + ([] if size is None else ["-s", str(size)])
    with open(nff_path, "w") as output:
        subprocess.run(command, check=True, stdout=output, cwd=generators)


def tracer_path(name: str) -> pathlib.Path:
    return ROOT / "build" / "release" / name


def median_seconds(command: list, runs: int) -> float:
    """Median wall time of `runs` runs of a command (which must succeed)."""
    times = []
    for _ in range(runs):
        started = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def render_corner_rays(
    scn_path: pathlib.Path, image_path: pathlib.Path, stats_path: pathlib.Path, threads: int
) -> dict:
    """Renders the corner-ray scene (N+1 rays a side) and averages each 2 x 2 block of corner
    samples into a pixel: upstream's procedure. Writes the N x N PNG; returns tracer's stats."""
    from tracer_tools.xcheck import (  # noqa: F401  (mitsuba_render sets the variant images reads with)
        images,
        mitsuba_render,
    )

    exr = image_path.with_suffix(".corners.exr")
    command = [tracer_path("tracer"), scn_path, "-o", exr, "-q", "--threads", str(threads), "--stats-json", stats_path]
    subprocess.run([str(c) for c in command], check=True)
    corners = images.read_exr(exr).astype(np.float64)
    pixels = (corners[:-1, :-1] + corners[1:, :-1] + corners[:-1, 1:] + corners[1:, 1:]) / 4
    images.write_png(image_path, pixels)
    exr.unlink()
    return json.loads(stats_path.read_text())


def with_spd_rules(scn_path: pathlib.Path, out_path: pathlib.Path) -> None:
    """The scene with `spawn_rules spd` in its render block (upstream's rules 8 and 10)."""
    with_render_key(scn_path, out_path, "spawn_rules spd")


def ray_counts(scn_path: pathlib.Path, stats_path: pathlib.Path, threads: int) -> dict:
    """tracer's ray counts for a scene (`--stats-json`'s rays), its image thrown away."""
    image = stats_path.with_suffix(".exr")
    command = [
        tracer_path("tracer"),
        scn_path,
        "-o",
        image,
        "-q",
        "--threads",
        str(threads),
        "--stats-json",
        stats_path,
    ]
    subprocess.run([str(c) for c in command], check=True)
    image.unlink()
    return json.loads(stats_path.read_text())["rays"]


def bench(scn_path: pathlib.Path, threads: int, runs: int) -> dict:
    """tracer_bench's in-process timings (median render, build) of a scene."""
    command = [tracer_path("tracer_bench"), scn_path, "--threads", str(threads), "--runs", str(runs), "--json"]
    done = subprocess.run([str(c) for c in command], check=True, capture_output=True, text=True)
    return json.loads(done.stdout)


def crosscheck(scn_path: pathlib.Path, folder: pathlib.Path, peer: str = "mitsuba") -> dict:
    """tools/crosscheck's report (tracer against Mitsuba 3, or `peer` povray, at the scene's
    size, 1 spp)."""
    environment = {
        **os.environ,
        "TRACER_BIN": str(tracer_path("tracer")),
        "PYTHONPATH": str(ROOT / "tools"),
    }
    command = [sys.executable, "-m", "tracer_tools.xcheck.crosscheck", str(scn_path), "--out", str(folder), "--json"]
    command += ["--with", peer]
    done = subprocess.run(command, capture_output=True, text=True, env=environment)
    if done.returncode not in (0, 1):  # 1: over a threshold, still reported
        raise RuntimeError(f"tools/crosscheck {scn_path} failed:\n{done.stderr}")
    return json.loads(done.stdout)


def perturbed_eye_scene(scn_path: pathlib.Path, out_path: pathlib.Path, offset: np.ndarray) -> None:
    """A copy of the scene with the camera's eye moved by `offset` (write it beside the scene)."""
    text = scn_path.read_text()

    def moved(match: re.Match) -> str:
        eye = [float(v) + d for v, d in zip(match.group(1).split(","), offset, strict=True)]
        return "eye (" + ", ".join(f"{v:.17g}" for v in eye) + ")"

    text, count = re.subn(r"eye \(([^)]*)\)", moved, text, count=1)
    if count != 1:
        raise RuntimeError(f"{scn_path}: no camera eye to move")
    out_path.write_text(text)


def unstable_pixels(
    scn_path: pathlib.Path, folder: pathlib.Path, relative: float, trials: int = 16, threads: int = 2
) -> np.ndarray:
    """Pixels whose 8-bit value moves by more than 2 levels when the eye moves by `relative` times
    its distance from the origin (at least 1), in any of `trials` random directions: there a
    renderer whose rays are moved that far (float32 Mitsuba) cannot be expected to agree."""
    from PIL import Image

    base_png = folder / "tracer_centres.png"
    subprocess.run(
        [str(tracer_path("tracer")), str(scn_path), "-o", str(base_png), "-q", "--threads", str(threads)], check=True
    )
    base = np.asarray(Image.open(base_png).convert("RGB")).astype(int)
    eye = re.search(r"eye \(([^)]*)\)", scn_path.read_text()).group(1)
    scale = max(1.0, float(np.linalg.norm([float(v) for v in eye.split(",")])))
    generator = np.random.default_rng(1987)
    unstable = np.zeros(base.shape[:2], dtype=bool)
    for trial in range(trials):
        direction = generator.normal(size=3)
        offset = direction / np.linalg.norm(direction) * relative * scale
        moved_scn = scn_path.with_name(f"{scn_path.stem}.perturbed.scn")  # beside it: same mesh paths
        perturbed_eye_scene(scn_path, moved_scn, offset)
        png = folder / f"perturbed{trial}.png"
        subprocess.run(
            [str(tracer_path("tracer")), str(moved_scn), "-o", str(png), "-q", "--threads", str(threads)], check=True
        )
        image = np.asarray(Image.open(png).convert("RGB")).astype(int)
        unstable |= np.abs(image - base).max(axis=2) > 2
        moved_scn.unlink()
        png.unlink()
    return unstable


def agreement_on_stable_pixels(folder: pathlib.Path, unstable: np.ndarray) -> dict:
    """Share of the well-conditioned pixels where tracer and Mitsuba differ by more than 2 levels."""
    from PIL import Image

    tracer = np.asarray(Image.open(folder / "tracer.png").convert("RGB")).astype(int)
    mitsuba = np.asarray(Image.open(folder / "mitsuba.png").convert("RGB")).astype(int)
    over = np.abs(tracer - mitsuba).max(axis=2) > 2
    stable = ~unstable
    return {
        "unstable": int(unstable.sum()),
        "over_2_stable": int((over & stable).sum()),
        "over_2_stable_share": float((over & stable).sum() / max(1, stable.sum())),
        "over_2_unstable": int((over & unstable).sum()),
    }


def without_refraction(scn_path: pathlib.Path, out_path: pathlib.Path) -> None:
    """A copy of the scene with kt and ior removed, for embree_scene, which has no refraction
    (write it beside the scene)."""
    out_path.write_text(re.sub(r"\s+kt \S+\s+ior \S+", "", scn_path.read_text()))


def compare_with_embree(
    bench_folder: pathlib.Path,
    embree: pathlib.Path,
    scn_path: pathlib.Path,
    pairs: int,
    runs: int,
    json_path: pathlib.Path,
) -> dict:
    """compare_scene.py's summary (tracer / Embree, alternating, 2 threads), or its refusal."""
    json_path.unlink(missing_ok=True)
    command = [
        sys.executable,
        str(bench_folder / "compare_scene.py"),
        str(ROOT),
        str(scn_path),
        "--embree",
        str(embree),
        "--pairs",
        str(pairs),
        "--runs",
        str(runs),
        "--json-out",
        str(json_path),
    ]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        return {"refused": (done.stderr.strip() or done.stdout.strip()).splitlines()[-1]}
    return json.loads(json_path.read_text().splitlines()[-1])


def build_embree(bench_folder: pathlib.Path, build_folder: pathlib.Path) -> pathlib.Path:
    """embree_scene built by the bench's build.sh (its Debian packages installed first)."""
    ensure_debian_packages(["cmake", "make", "g++", "libembree-dev", "libtbb-dev", "libtinyobjloader-dev"])
    executable = build_folder / "embree_scene"
    if not executable.exists():
        subprocess.run(["bash", str(bench_folder / "build.sh"), str(build_folder)], check=True, stdout=sys.stderr)
    return executable
