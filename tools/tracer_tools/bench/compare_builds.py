"""Two (or more) builds of trace_parts, run in turn (A B A B ...): the median time of each part
per build, and the median of the per-round ratios last build / first build. On a shared
machine only such side-by-side runs compare; 11-15 rounds bring the ratio's noise to ~1%.

    tools/bench compare-builds OLD/trace_parts NEW/trace_parts --rounds 15 [-- ARGS]

ARGS go to every build (for instance --full).
"""

import argparse
import re
import statistics
import subprocess
import sys

from tracer_tools import option_types

LINE = re.compile(r"^(\S+)\s+([\d.]+) ms", re.M)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("builds", type=option_types.free_text, nargs="+")
    parser.add_argument("--rounds", type=option_types.whole_number(1, 1_000_000), default=15)
    ours, extra = (
        (sys.argv[1:], [])
        if "--" not in sys.argv
        else (sys.argv[1 : sys.argv.index("--")], sys.argv[sys.argv.index("--") + 1 :])
    )
    options = parser.parse_args(ours)
    times = {build: {} for build in options.builds}
    for _ in range(options.rounds):
        for build in options.builds:
            output = subprocess.run([build] + extra, capture_output=True, text=True, check=True).stdout
            for part, ms in LINE.findall(output):
                times[build].setdefault(part, []).append(float(ms))
    first, last = options.builds[0], options.builds[-1]
    print(
        f"{'part':16}" + "".join(f"{'build ' + str(i + 1):>12}" for i in range(len(options.builds))) + "   last/first"
    )
    for part in times[first]:
        medians = "".join(f"{statistics.median(times[b][part]):12.2f}" for b in options.builds)
        ratio = statistics.median(b / a for a, b in zip(times[first][part], times[last][part], strict=False))
        print(f"{part:16}{medians}   {ratio:.3f}")


if __name__ == "__main__":
    main()
