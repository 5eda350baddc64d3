#!/usr/bin/env python3
"""A tracer that fails: as the real one (REAL_TRACER), except that its first FLAKY_FAILURES workers
(counted in the file FLAKY_STATE, shared by every process) read one tile request and stop with an
error instead of rendering it, as a crashed or killed tracer would."""

import fcntl
import os
import sys

real = os.environ["REAL_TRACER"]
if "--region-list" in sys.argv:
    with open(os.environ["FLAKY_STATE"], "a+") as state:
        fcntl.flock(state, fcntl.LOCK_EX)
        state.seek(0)
        failures = len(state.read())
        if failures < int(os.environ["FLAKY_FAILURES"]):
            state.write("x")
            state.flush()
            fcntl.flock(state, fcntl.LOCK_UN)
            sys.stdin.readline()
            print("tracer: error: simulated crash", file=sys.stderr)
            sys.exit(3)
os.execv(real, [real, *sys.argv[1:]])
