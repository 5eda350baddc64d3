"""tracer's tools in Python: the cross-checks against Mitsuba 3 (xcheck), the NFF importer (nff),
the SPD suite (spd), the render farm (farm), the benchmarks (bench) and the generators of test
scenes (scenes). The commands a user runs are declared in pyproject.toml's [project.scripts] and
started by tools/<command> (see tools/README.md)."""

import pathlib

# The checkout this package sits in (tools/tracer_tools/__init__.py -> the checkout's root).
ROOT = pathlib.Path(__file__).resolve().parents[2]
