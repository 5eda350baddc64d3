"""xcheck: cross-checks tracer's images against Mitsuba 3 (see docs/crosscheck.md)."""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Callable

# The plugin names the converted XML uses and xcheck.plugins registers.
PHONG_PLUGIN = "tracer_phong"
WHITTED_PLUGIN = "tracer_whitted"


OTHER_FAILURE = 5  # the exit code of failures without a code of their own (see crosscheck.py)


class ToolError(Exception):
    """A problem the command-line tools report in one line and exit with `exit_code`."""

    exit_code = OTHER_FAILURE


class PeerCannotExpress(ToolError):
    """The scene uses what the peer renderer has no way to express (solids for Mitsuba 3): the
    cross-check skips it, saying why, instead of failing."""


class MitsubaMissing(ToolError):
    """Mitsuba 3 (or Dr.Jit) cannot be imported."""

    exit_code = 4


def run_reporting_errors(tool: str, work: Callable[[], int]) -> int:
    """Runs work() and returns its exit code; a ToolError, OSError or failed subprocess becomes
    one line `tool: error: ...` on stderr and its exit code."""
    try:
        return work()
    except ToolError as error:
        print(f"{tool}: error: {error}", file=sys.stderr)
        return error.exit_code
    except (OSError, subprocess.CalledProcessError) as error:
        print(f"{tool}: error: {error}", file=sys.stderr)
        return OTHER_FAILURE
