"""The cross-check's steps on stderr: each step's name when it starts, a line every few seconds
while it runs (Mitsuba's and POV-Ray's renders give no progress of their own), and its time."""

from __future__ import annotations

import contextlib
import sys
import threading
import time
from collections.abc import Iterator

HEARTBEAT_SECONDS = 10.0


@contextlib.contextmanager
def step(tool: str, what: str, heartbeat: float = HEARTBEAT_SECONDS) -> Iterator[None]:
    """Prints `tool: WHAT...`, then `tool: still WHAT (N s)` every `heartbeat` seconds until the
    block ends, then `tool: WHAT: done in N s`."""
    start = time.monotonic()
    finished = threading.Event()
    print(f"{tool}: {what}...", file=sys.stderr, flush=True)

    def beat() -> None:
        while not finished.wait(heartbeat):
            print(f"{tool}: still {what} ({time.monotonic() - start:.0f} s)", file=sys.stderr, flush=True)

    thread = threading.Thread(target=beat, daemon=True)
    thread.start()
    try:
        yield
    finally:
        finished.set()
        thread.join()
    print(f"{tool}: {what}: done in {time.monotonic() - start:.1f} s", file=sys.stderr, flush=True)
