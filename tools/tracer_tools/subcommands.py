"""A command whose first argument names one of several modules of a package (tools/bench NAME,
tools/make-scene NAME): the table of names, the usage listing and the dispatch, written once."""

import importlib
import sys


def run(command: str, package: str, table: dict[str, tuple[str, str]]) -> int:
    """Runs main() of `package`.MODULE for the name in sys.argv[1] (table: name -> (MODULE, meaning)),
    with that name taken out of sys.argv; without a known name, lists the table (exit 0 if none
    was given, 2 if the name is unknown)."""
    if len(sys.argv) < 2 or sys.argv[1] not in table:
        print(f"usage: {command} NAME [ARGS...]   ({command} NAME --help for its options)\n", file=sys.stderr)
        for name, (_, meaning) in table.items():
            print(f"  {name:15} {meaning}", file=sys.stderr)
        return 0 if len(sys.argv) < 2 else 2
    name = sys.argv.pop(1)
    sys.argv[0] = f"{command} {name}"
    return importlib.import_module(f"{package}.{table[name][0]}").main() or 0
