"""The farm's progress on stderr: tiles (or frames) done, how many a second, time left."""

from __future__ import annotations

import sys
import time


class Progress:
    """One line redrawn in place on a terminal; elsewhere a line at most every few seconds."""

    def __init__(self, tiles: int, quiet: bool = False, every_s: float = 5.0, unit: str = "tiles") -> None:
        self.tiles, self.done, self.quiet, self.every_s, self.unit = tiles, 0, quiet, every_s, unit
        self.start = self.shown = time.perf_counter()
        self.terminal = sys.stderr.isatty()

    def text(self) -> str:
        elapsed = max(time.perf_counter() - self.start, 1e-9)
        rate = self.done / elapsed
        left = (self.tiles - self.done) / rate if rate > 0 else float("inf")
        return f"farm: {self.done}/{self.tiles} {self.unit}, {rate:.1f} {self.unit}/s, about {left:.0f} s left"

    def tile_done(self, count: int = 1) -> None:
        self.done += count
        if self.quiet:
            return
        now = time.perf_counter()
        if self.terminal:
            sys.stderr.write("\r" + self.text() + "\033[K")
        elif now - self.shown >= self.every_s or self.done == self.tiles:
            sys.stderr.write(self.text() + "\n")
        else:
            return
        self.shown = now
        sys.stderr.flush()

    def finish(self) -> None:
        if self.terminal and not self.quiet:
            sys.stderr.write("\r\033[K")
            sys.stderr.flush()
