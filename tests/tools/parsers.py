"""Every command-line parser of the Python tools, collected by running each command's main() up
to the moment it parses its arguments (argparse's parse_args is intercepted there, so that no
tool does any work): the tools are walked as they are, without a registry to keep in step."""

from __future__ import annotations

import argparse
import contextlib
import importlib
import sys
import tomllib
from collections.abc import Iterator

from tracer_tools import ROOT


class _Parsed(Exception):
    def __init__(self, parser: argparse.ArgumentParser):
        self.parser = parser


def _commands() -> dict[str, str]:
    with open(ROOT / "pyproject.toml", "rb") as file:
        return tomllib.load(file)["project"]["scripts"]


def _subcommands(module) -> dict[str, tuple[str, str]] | None:
    """The NAME table of a command that dispatches to modules (tools/bench NAME), if it is one."""
    for value in vars(module).values():
        if isinstance(value, dict) and value and all(isinstance(v, tuple) and len(v) == 2 for v in value.values()):
            return value
    return None


@contextlib.contextmanager
def _intercepted() -> Iterator[None]:
    original_known = argparse.ArgumentParser.parse_known_args

    def stop(self, args=None, namespace=None):
        raise _Parsed(self)

    argparse.ArgumentParser.parse_known_args = stop
    try:
        yield
    finally:
        argparse.ArgumentParser.parse_known_args = original_known


def _parser_of(entry, argv0: str, argv: list[str]) -> argparse.ArgumentParser | None:
    saved = sys.argv
    sys.argv = [argv0, *argv]
    try:
        with _intercepted():
            entry()
    except _Parsed as parsed:
        return parsed.parser
    except SystemExit:
        return None
    finally:
        sys.argv = saved
    return None


def all_parsers() -> Iterator[tuple[str, argparse.ArgumentParser]]:
    """(command, parser) for every tool and every NAME of the tools that take one."""
    for command, target in _commands().items():
        module_name, function = target.split(":")
        module = importlib.import_module(module_name)
        table = _subcommands(module)
        if table:
            package = module_name.rsplit(".", 1)[0]
            for name, (submodule, _) in table.items():
                sub = importlib.import_module(f"{package}.{submodule}")
                parser = _parser_of(sub.main, f"tools/{command} {name}", [])
                if parser is not None:
                    yield f"{command} {name}", parser
            continue
        parser = _parser_of(getattr(module, function), f"tools/{command}", [])
        if parser is not None:
            yield command, parser
