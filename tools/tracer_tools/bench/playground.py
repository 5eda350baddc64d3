"""Issue 59's targets for the playground, in Debian's headless Chromium on this machine:

1. task2 at its 1200 x 800 in the browser with one worker (`?workers=1`: the whole image's render,
   band by band, as the page reports it) against the command line's render loop on one thread
   (`--threads 1`, --stats-json's render seconds), alternated A B A B (target: at most 2x); beside
   it, the page's own workers (one per core) against the command line on as many threads;
2. edit to preview on screen, on task2: from the edit to its first pixels on the canvas (its
   preview, or the whole image's first band if that comes first; the page's 40 ms pause after
   typing included), median of 15 edits (target: 150 ms);
3. first image: from the page's start of loading (navigation) to the first image on screen
   (task2's preview), served from 127.0.0.1, a fresh browser (empty cache) each time, median of 5
   (target: 1.5 s);
4. the site's size, each file gzip -9 as a static host sends it, without the gallery's meshes
   (target: 3 MB);
5. every gallery scene rendered in the browser against the command line's 8-bit image: the
   pixels that differ (target: none, or each difference explained).

    tools/bench playground [--pairs 5] [--skip-gallery]

The site is built first (tools/playground build). The report goes to standard output, as
committed in docs/bench/bench-playground.md.
"""

import argparse
import base64
import gzip
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import TRACER, git, machine
from tracer_tools.playground import site

TASK2 = ROOT / "scenes" / "task2.scn"
WAIT = 600


def browser() -> object:
    return site.chromium(script_timeout=WAIT)


def wait(driver: object, condition: Callable) -> object:
    from selenium.webdriver.support.ui import WebDriverWait

    return WebDriverWait(driver, WAIT, poll_frequency=0.01).until(condition)


def drawn(driver: object) -> list:
    return driver.execute_script("return window.tracerPlayground ? window.tracerPlayground.drawn : []")


def latest_final(driver: object) -> dict | None:
    """The drawn entry of the latest job's whole image, once there (or the diagnostics shown)."""
    state = driver.execute_script(
        "const p = window.tracerPlayground; if (!p || p.jobText() !== p.view.state.doc.toString()) return null;"
        "return [p.jobs(), document.getElementById('diagnostics').textContent]"
    )
    if not state:
        return None
    finals = [d for d in drawn(driver) if d["id"] == state[0] and d["final"]]
    return finals[0] if finals else ({"diagnostics": state[1]} if state[1] else None)


def edit(driver: object, text: str) -> None:
    driver.execute_script(
        "const v = window.tracerPlayground.view; window.editAt = performance.now();"
        "v.dispatch({changes: {from: 0, to: v.state.doc.length, insert: arguments[0]}});",
        text,
    )


def native_render_seconds(folder: Path, threads: int) -> float:
    stats = folder / "stats.json"
    command = [TRACER, TASK2, "-o", folder / "task2.png", "-q", "--threads", threads, "--stats-json", stats]
    subprocess.run([str(c) for c in command], check=True)
    return json.loads(stats.read_text())["render_seconds"]


def canvas_rgb(driver: object) -> bytes:
    data = driver.execute_script(
        "const c = document.getElementById('image');"
        "const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
        "let s = ''; for (let i = 0; i < d.length; i += 4) s += String.fromCharCode(d[i], d[i+1], d[i+2]);"
        "return btoa(s);"
    )
    return base64.b64decode(data)


def native_rgb(scene: Path, folder: Path) -> bytes:
    out = folder / "native.ppm"
    subprocess.run([str(TRACER), str(scene), "-o", str(out), "-q"], check=True)
    return out.read_bytes().split(b"\n", 3)[3]


def site_size(folder: Path) -> tuple[int, int]:
    """The site's gzip -9 bytes without the gallery's meshes, and the meshes' own."""
    total = sum(
        len(gzip.compress(p.read_bytes(), 9)) for p in folder.iterdir() if p.is_file() and p.name != "tracer.data"
    )
    files = [p for p in (ROOT / "scenes").rglob("*") if p.is_file()]
    others = b"".join(p.read_bytes() for p in files if p.suffix.lower() != ".obj")
    meshes = b"".join(p.read_bytes() for p in files if p.suffix.lower() == ".obj")
    return total + len(gzip.compress(others, 9)), len(gzip.compress(meshes, 9))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pairs", type=option_types.whole_number(1, 1000), default=5)
    parser.add_argument("--skip-gallery", action="store_true", help="leave out target 5 (the longest)")
    args = parser.parse_args()
    print(f"# tools/bench playground: {time.strftime('%Y-%m-%d')}, {git('rev-parse', '--short', 'HEAD')}")
    print(f"# machine: {machine()}; {shutil.which('chromium')} headless; medians\n")
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        folder = scratch / "site"
        site.build(argparse.Namespace(out=str(folder), quiet=True))
        server = site.BackgroundServer(folder)
        url = server.url
        print("| target | measured | met |\n|---|---|---|")
        text = TASK2.read_text()
        # 1. task2 in the browser against the command line: one worker against one thread (the
        # module's own speed), then the page's workers (one per core) against as many threads.
        cores = len(os.sched_getaffinity(0))
        for workers, threads in ((1, 1), (min(cores, 4), min(cores, 4))):
            driver = browser()
            driver.get(f"{url}?workers={workers}")
            wait(driver, latest_final)
            ratios, browser_s, native_s = [], [], []
            for pair in range(args.pairs):
                edit(driver, text + f"# render {pair}\n")
                browser_s.append(wait(driver, latest_final)["milliseconds"] / 1000)
                native_s.append(native_render_seconds(scratch, threads))
                ratios.append(browser_s[-1] / native_s[-1])
            driver.quit()
            ratio = statistics.median(ratios)
            seconds = f"browser {statistics.median(browser_s):.3f} s, native {statistics.median(native_s):.3f} s"
            figures = f"{ratio:.2f}x ({seconds}; ratios {' '.join(f'{r:.2f}' for r in ratios)})"
            if workers == 1:
                print(
                    f"| task2 1200 x 800, one worker, within 2x the native single-thread render | {figures} | "
                    f"{'yes' if ratio <= 2 else 'no'} |"
                )
            else:
                print(
                    f"| (beside it) task2 with the page's {workers} workers against the native render on {threads} "
                    f"threads | {figures} | - |"
                )
        driver = browser()
        driver.get(url)
        wait(driver, latest_final)
        # 2. Edit to preview on screen.
        previews = []
        for n in range(15):
            edit(driver, text.replace("max_depth 4", f"max_depth {3 + n % 2}") + f"# edit {n}\n")

            def first_paint(d: object) -> dict | None:
                return d.execute_script(
                    "const p = window.tracerPlayground; if (p.jobText() !== p.view.state.doc.toString()) return null;"
                    "return p.firstPaints.find((f) => f.id === p.jobs()) || null"
                )

            entry = wait(driver, first_paint)
            previews.append(entry["at"] - driver.execute_script("return window.editAt"))
            wait(driver, latest_final)
        preview = statistics.median(previews)
        print(
            f"| edit to preview on screen, task2, <= 150 ms | {preview:.0f} ms (min {min(previews):.0f}, max "
            f"{max(previews):.0f}, of 15) | {'yes' if preview <= 150 else 'no'} |"
        )
        driver.quit()
        # 3. First image after the page starts loading, a fresh browser each time.
        firsts = []
        for _ in range(5):
            fresh = browser()
            fresh.get(url)
            wait(fresh, lambda d: d.execute_script("return window.tracerPlayground?.firstPaints.length"))
            firsts.append(fresh.execute_script("return window.tracerPlayground.firstPaints[0].at") / 1000)
            fresh.quit()
        first = statistics.median(firsts)
        print(
            f"| first image <= 1.5 s after the page starts loading | {first:.2f} s "
            f"({' '.join(f'{f:.2f}' for f in firsts)}) | {'yes' if first <= 1.5 else 'no'} |"
        )
        # 4. The site's size.
        size, meshes = site_size(folder)
        print(
            f"| the site <= 3 MB compressed, without the gallery's meshes | {size / 1e6:.2f} MB (the meshes "
            f"{meshes / 1e6:.2f} MB more) | {'yes' if size <= 3e6 else 'no'} |"
        )
        # 5. Every gallery scene against the command line's pixels.
        if not args.skip_gallery:
            driver = browser()
            driver.get(url)
            wait(driver, latest_final)
            scenes = driver.execute_script("return [...document.getElementById('gallery').options].map(o => o.value)")
            differing = {}
            for path in scenes:
                driver.execute_script(
                    "const g = document.getElementById('gallery'); g.value = arguments[0];"
                    "g.dispatchEvent(new Event('change'));",
                    path,
                )
                scene = ROOT / path.removeprefix("/")
                wanted = scene.read_text()
                wait(
                    driver,
                    lambda d, w=wanted: d.execute_script("return window.tracerPlayground.view.state.doc.toString()")
                    == w,
                )
                final = wait(driver, latest_final)
                if "diagnostics" in final:
                    differing[path] = "error: " + final["diagnostics"].splitlines()[0]
                    continue
                mine, theirs = canvas_rgb(driver), native_rgb(scene, scratch)
                pixels = sum(mine[i : i + 3] != theirs[i : i + 3] for i in range(0, min(len(mine), len(theirs)), 3))
                if pixels or len(mine) != len(theirs):
                    differing[path] = f"{pixels} pixels differ"
            driver.quit()
            same = len(scenes) - len(differing)
            print(
                f"| every gallery scene's pixels as the native build's | {same} of {len(scenes)} identical"
                + "".join(f"; {p}: {why}" for p, why in differing.items())
                + f" | {'yes' if not differing else 'no'} |"
            )
        server.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
