"""python -m tracer_tools COMMAND [ARGS...]: runs one of the commands that pyproject.toml's
[project.scripts] declares (the table is read there, so that it is written once), as
tools/COMMAND does."""

import importlib
import sys
import tomllib

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
    return getattr(importlib.import_module(module), function)() or 0


if __name__ == "__main__":
    sys.exit(main())
