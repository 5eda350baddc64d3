"""The scene language against POV-Ray 3.7's parser, on the same loops written in each: each case
run alternately in both (A B A B ...), medians reported with peak memory. tracer's time is the
whole `tracer --check` process (start, parse, run, check); POV-Ray's is its reported Parse Time
(its start and 1x1-pixel render are not counted). Output as committed in docs/bench/bench-language.md.

    tools/bench language [--runs 3] [--povray povray]
"""

import argparse
import datetime
import os
import re
import shutil
import statistics
import subprocess
import tempfile
import time

from tracer_tools import ROOT, option_types
from tracer_tools.bench.common import TRACER, machine

POV_HEADER = (
    "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n"
    "camera { location <0, 0, -50> look_at <0, 0, 0> }\nlight_source { <0, 30, -30> color rgb 1 }\n"
)
SCN_HEADER = "camera { eye (0, 0, 50) lookat (0, 0, 0) }\nlight { position (0, 30, 30) }\n"

# name: (what it is, tracer's scene, POV-Ray's scene or None)
CASES = {
    "lets": (
        "10^7 iterations of a loop whose body is one name given a value",
        SCN_HEADER + "sphere { center (0, 0, 0) radius 1 material { kd 1 } }\n"
        "for i in 0..10000000 { let x = i * 2 }\n",
        POV_HEADER + "sphere { <0, 0, 0>, 1 pigment { rgb 1 } }\n"
        "#declare I = 0;\n#while (I < 10000000)\n  #declare X = I * 2;\n  #declare I = I + 1;\n#end\n",
    ),
    "accumulate": (
        "10^7 iterations of a loop adding to one name (total = total + i)",
        SCN_HEADER + "sphere { center (0, 0, 0) radius 1 material { kd 1 } }\n"
        "let total = 0\nfor i in 0..10000000 { total = total + i }\n",
        POV_HEADER + "sphere { <0, 0, 0>, 1 pigment { rgb 1 } }\n"
        "#declare T = 0;\n#declare I = 0;\n#while (I < 10000000)\n  #declare T = T + I;\n  #declare I = I + 1;\n#end\n",
    ),
    "spheres": (
        "10^6 spheres from two nested loops, sin and cos in their centres",
        SCN_HEADER + "material m { kd 1 }\nfor i in 0..1000 {\n  for j in 0..1000 {\n"
        "    sphere { center (i * 0.01 + sin(j), cos(i) + j * 0.01, sin(i + j)) radius 0.01 material m }\n  }\n}\n",
        POV_HEADER + "#declare I = 0;\n#while (I < 1000)\n  #declare J = 0;\n  #while (J < 1000)\n"
        "    sphere { <I * 0.01 + sin(radians(J)), cos(radians(I)) + J * 0.01, sin(radians(I + J))>, 0.01 "
        "pigment { rgb 1 } }\n    #declare J = J + 1;\n  #end\n  #declare I = I + 1;\n#end\n",
    ),
    "task2": ("scenes/task2.scn, the assignment's scene", None, None),
    "sphereflake": ("scenes/spd/procedural/balls.scn -D size=5: 66,430 spheres by recursion", None, None),
}


def run_measured(command: list) -> tuple[float, int, str]:
    """Runs `command` alone; returns its wall time in seconds, its peak resident memory in bytes
    and its standard error. The peak is measured by GNU time (/usr/bin/time): a child of this
    Python process would start with Python's own pages counted."""
    timed = ["/usr/bin/time", "-f", "peak %M KB", *map(str, command)]
    start = time.perf_counter()
    done = subprocess.run(timed, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, errors="replace")
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"{command[0]} failed:\n{done.stderr}")
    peak = re.findall(r"peak (\d+) KB", done.stderr)
    return seconds, int(peak[-1]) * 1024, done.stderr


def tracer_command(name: str, folder: str) -> list:
    if name == "task2":
        return [TRACER, "--check", ROOT / "scenes" / "task2.scn"]
    if name == "sphereflake":
        return [TRACER, "--check", ROOT / "scenes" / "spd" / "procedural" / "balls.scn", "-D", "size=5"]
    return [TRACER, "--check", os.path.join(folder, name + ".scn")]


def povray_parse(povray: str, scene: str) -> tuple[float, int]:
    """POV-Ray's reported Parse Time and its peak memory, for `scene` rendered at 1x1 pixels."""
    _, memory, text = run_measured([povray, f"+I{scene}", "+O/dev/null", "+W1", "+H1", "-D", "+WT2"])
    found = re.search(r"Parse Time:.*\(([0-9.]+) seconds\)", text)
    if not found:
        raise SystemExit("POV-Ray printed no Parse Time:\n" + text[-2000:])
    return float(found.group(1)), memory


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=option_types.whole_number(1, 1_000_000), default=3)
    parser.add_argument("--povray", type=option_types.free_text, default="povray")
    parser.add_argument(
        "cases", type=option_types.free_text, nargs="*", default=list(CASES), help="of: " + ", ".join(CASES)
    )
    args = parser.parse_args()
    povray = shutil.which(args.povray)
    if not TRACER.exists():
        subprocess.run([ROOT / "tools" / "bootstrap"], check=True, stdout=subprocess.DEVNULL)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=ROOT)
    print(f"# tools/bench language: {datetime.date.today()}, {commit.stdout.strip()}")
    print(f"# machine: {machine()}; {args.runs} runs each, alternating; medians")
    print(f"# POV-Ray: {povray or 'not found (its columns are empty)'}\n")
    print("| case | tracer --check | peak memory | POV-Ray parse | POV-Ray memory | POV-Ray / tracer |")
    print("|---|--:|--:|--:|--:|--:|")
    with tempfile.TemporaryDirectory() as folder:
        for name in args.cases:
            meaning, scene, pov = CASES[name]
            if scene:
                with open(os.path.join(folder, name + ".scn"), "w") as out:
                    out.write(scene)
            if pov:
                with open(os.path.join(folder, name + ".pov"), "w") as out:
                    out.write(pov)
            ours, theirs = [], []
            for _ in range(args.runs):
                seconds, memory, _ = run_measured(tracer_command(name, folder))
                ours.append((seconds, memory))
                if pov and povray:
                    theirs.append(povray_parse(povray, os.path.join(folder, name + ".pov")))
            ours_s = statistics.median(s for s, _ in ours)
            ours_mb = statistics.median(m for _, m in ours) / 1e6
            row = f"| {name}: {meaning} | {ours_s:.3f} s | {ours_mb:.1f} MB |"
            if theirs:
                theirs_s = statistics.median(s for s, _ in theirs)
                theirs_mb = statistics.median(m for _, m in theirs) / 1e6
                row += f" {theirs_s:.3f} s | {theirs_mb:.1f} MB | {theirs_s / ours_s:.1f}x |"
            else:
                row += " – | – | – |"
            print(row, flush=True)
    return 0
