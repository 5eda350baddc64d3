"""Fails, naming each, when a function of the C++ under src/ is longer than the limit (80 lines
from its signature to its closing brace, as lizard counts them), so that every function fits a
screen. Usage: python -m tracer_tools.lint.function_length [--limit N] [FOLDER ...]"""

import argparse
import pathlib
import sys

import lizard

SOURCE_SUFFIXES = (".cpp", ".h", ".inl")


def long_functions(folders: list[pathlib.Path], limit: int) -> list[str]:
    """'path:line: name is N lines' for each function over `limit` lines, in path order."""
    found = []
    for folder in folders:
        for path in sorted(p for p in folder.rglob("*") if p.suffix in SOURCE_SUFFIXES and p.is_file()):
            # lizard picks its reader by the name's suffix: an .inl is C++ too.
            name = str(path) if path.suffix != ".inl" else f"{path}.h"
            analysis = lizard.analyze_file.analyze_source_code(name, path.read_text(encoding="utf-8"))
            for function in analysis.function_list:
                if function.length > limit:
                    found.append(f"{path}:{function.start_line}: {function.name} is {function.length} lines")
    return found


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="function_length", description=__doc__)
    parser.add_argument("--limit", type=int, default=80, help="the most lines a function may have (default 80)")
    parser.add_argument("folders", nargs="*", type=pathlib.Path, default=[pathlib.Path("src")])
    arguments = parser.parse_args(argv)
    missing = [str(folder) for folder in arguments.folders if not folder.is_dir()]
    if missing:
        parser.error(f"no such folder: {', '.join(missing)}")
    found = long_functions(arguments.folders, arguments.limit)
    for line in found:
        print(f"  {line}", file=sys.stderr)
    if found:
        print(
            f"lint: {len(found)} functions over {arguments.limit} lines: split them into named steps", file=sys.stderr
        )
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
