"""Every option of every Python tool takes a checked value (tracer_tools.option_types) or a
fixed choice, and hostile values end as argparse's one-line refusal (exit 2), never as a
traceback or a hang: the walk goes through the tools' own parsers (parsers.py)."""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import threading

import pytest
from parsers import all_parsers

from tracer_tools import ROOT, option_types
from tracer_tools.__main__ import run_guarded

PARSERS = list(all_parsers())
VALUE_ACTIONS = [
    (command, action)
    for command, parser in PARSERS
    for action in parser._actions
    if not isinstance(action, argparse._HelpAction) and action.nargs != 0
]
HOSTILE = [
    "",
    "abc",
    "nan",
    "inf",
    "-inf",
    "1e400",
    "-1",
    "99999999999999999999",
    "\x7f",
    "/dev/zero",
    "/nonexistent/x",
]
NUMBER_TYPES = ("whole number", "number")


def label(command: str, action: argparse.Action) -> str:
    return f"{command} {'/'.join(action.option_strings) or action.dest}"


def test_the_walk_finds_every_tool():
    commands = {command.split()[0] for command, _ in PARSERS}
    assert {"crosscheck", "farm", "preview", "lsp", "bench", "make-scene", "spd", "nff2scn"} <= commands
    assert len(VALUE_ACTIONS) > 100


@pytest.mark.parametrize("command,action", VALUE_ACTIONS, ids=[label(c, a) for c, a in VALUE_ACTIONS])
def test_every_option_value_is_checked(command, action):
    checked = getattr(action.type, "__module__", None) == option_types.__name__
    assert checked or action.choices, f"{label(command, action)} takes any value: give it a type of option_types"


def refusal_or_value(convert, text: str, fifo: str):
    """convert(text) within 5 s: its value, or the ArgumentTypeError argparse turns into a message."""
    outcome: list = []

    def run():
        try:
            outcome.append(convert(text))
        except argparse.ArgumentTypeError as error:
            outcome.append(error)

    worker = threading.Thread(target=run, daemon=True)
    worker.start()
    worker.join(5)
    assert not worker.is_alive(), f"checking {text!r} hangs"
    return outcome[0]


@pytest.mark.parametrize("command,action", VALUE_ACTIONS, ids=[label(c, a) for c, a in VALUE_ACTIONS])
def test_hostile_values_are_refused_in_one_line(command, action, tmp_path):
    if action.type is None:
        return  # a choice: argparse itself refuses anything else
    fifo = str(tmp_path / "fifo")
    os.mkfifo(fifo)
    for text in [*HOSTILE, fifo]:
        result = refusal_or_value(action.type, text, fifo)  # any other exception fails the test
        unbounded_real = action.type.__name__ == "number" and text == "99999999999999999999"
        if action.type.__name__ in NUMBER_TYPES and text != "-1" and not unbounded_real:
            assert isinstance(result, argparse.ArgumentTypeError), f"{label(command, action)} takes {text!r}"
        if text == "":
            assert isinstance(result, argparse.ArgumentTypeError), f"{label(command, action)} takes an empty value"
        if text in ("/dev/zero", fifo) and action.type in (option_types.existing_file, option_types.executable_file):
            assert isinstance(result, argparse.ArgumentTypeError), f"{label(command, action)} takes {text}"


def test_numbers_keep_their_bounds():
    assert option_types.port("0") == 0 and option_types.port("65535") == 65535
    for text in ("-1", "65536", "99999", "8000.5", "0x10"):
        with pytest.raises(argparse.ArgumentTypeError):
            option_types.port(text)
    between = option_types.real_number(0, 1, low_open=True)
    assert between("1") == 1.0
    with pytest.raises(argparse.ArgumentTypeError, match="above 0"):
        between("0")


def test_files_are_read_only_when_regular_and_bounded(tmp_path):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for path in (fifo, "/dev/zero", tmp_path):
        with pytest.raises(option_types.UnreadableFile):
            option_types.read_regular_file(path)
    big = tmp_path / "big"
    big.write_bytes(b"x" * 1000)
    with pytest.raises(option_types.UnreadableFile, match="more than the 999"):
        option_types.read_regular_file(big, limit=999)
    assert option_types.read_regular_file(big, limit=1000) == b"x" * 1000
    (tmp_path / "latin").write_bytes(b"caf\xe9")
    with pytest.raises(option_types.UnreadableFile, match="not UTF-8"):
        option_types.read_text_file(tmp_path / "latin")


def test_an_unchecked_failure_is_one_line_and_exit_70(capsys, monkeypatch):
    monkeypatch.delenv("TRACER_TOOLS_TRACEBACK", raising=False)

    def broken():
        return {}["missing"]

    assert run_guarded("tools/x", broken) == 70
    err = capsys.readouterr().err
    assert err.startswith("tools/x: internal error: KeyError: 'missing' (at test_tool_options.py:")
    assert "Traceback" not in err and err.count("\n") == 1

    def interrupted():
        raise KeyboardInterrupt

    assert run_guarded("tools/x", interrupted) == 130
    assert capsys.readouterr().err == "tools/x: interrupted\n"


def tool(*arguments: str) -> subprocess.CompletedProcess:
    """tools/NAME ARGUMENTS as the launcher runs it (without its build step), stdin closed."""
    return subprocess.run(
        [sys.executable, "-P", "-m", "tracer_tools", *arguments],
        capture_output=True,
        text=True,
        timeout=300,  # a hang bound, far above the second it takes on a busy machine
        stdin=subprocess.DEVNULL,
        cwd=ROOT,
    )


@pytest.mark.parametrize(
    "arguments,message",
    [
        (["preview", "x.scn", "--port", "99999"], "argument --port: must be between 0 and 65535, found 99999"),
        (["preview", "x.scn", "--port", "-1"], "argument --port: must be between 0 and 65535, found -1"),
        (["lsp", "--tracer", "/nonexistent"], "argument --tracer: cannot use /nonexistent: No such file or directory"),
        (["farm", "/dev/zero", "-o", "x.png"], "argument scene: /dev/zero is not a regular file"),
        (["crosscheck", "scenes/task2.scn", "--width", "1e400"], "argument --width: expects a whole number"),
        (["bench", "bvh", "--threads", "nan"], "argument --threads: expects a whole number, found 'nan'"),
    ],
)
def test_the_reported_cases_end_in_one_line_and_exit_2(arguments, message):
    result = tool(*arguments)
    assert result.returncode == 2, result.stderr
    assert message in result.stderr
    assert "Traceback" not in result.stderr
