"""python -m tracer_tools COMMAND [ARGS...]: runs one of the commands that pyproject.toml's
[project.scripts] declares (the table is read there, so that it is written once), as
tools/COMMAND does."""

import importlib
import os
import pathlib
import sys
import tomllib
import traceback
from collections.abc import Callable

from tracer_tools import ROOT


def commands() -> dict[str, str]:
    """Each command's name and its entry point ("package.module:function"), from pyproject.toml."""
    with open(ROOT / "pyproject.toml", "rb") as file:
        return tomllib.load(file)["project"]["scripts"]


def main() -> int:
    table = commands()
    if len(sys.argv) < 2 or sys.argv[1] not in table:
        print(f"usage: python -m tracer_tools COMMAND [ARGS...]; commands: {', '.join(table)}", file=sys.stderr)
        return 2
    name = sys.argv.pop(1)
    sys.argv[0] = f"tools/{name}"
    module, function = table[name].split(":")
    return run_guarded(f"tools/{name}", getattr(importlib.import_module(module), function))


def run_guarded(command: str, entry: Callable[[], int | None]) -> int:
    """Runs a command's entry point with the last line of defence against tracebacks: Ctrl-C ends
    it with exit 130 and one line; an exception its own checks did not turn into a message (a
    bug: every input is checked) is one line naming the bug, exit 70, and the traceback only
    with TRACER_TOOLS_TRACEBACK=1."""
    try:
        return entry() or 0
    except KeyboardInterrupt:
        print(f"{command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader of our output went away (| head): nothing to say to it
        sys.stderr.close()
        return 1
    except Exception as error:  # noqa: BLE001 - the one place that catches everything
        if os.environ.get("TRACER_TOOLS_TRACEBACK"):
            raise
        where = traceback.extract_tb(error.__traceback__)[-1]
        print(
            f"{command}: internal error: {type(error).__name__}: {error} "
            f"(at {pathlib.Path(where.filename).name}:{where.lineno}; "
            "TRACER_TOOLS_TRACEBACK=1 shows the traceback; please report it)",
            file=sys.stderr,
        )
        return 70


if __name__ == "__main__":
    sys.exit(main())
