"""The checked values of the tools' command lines, and the one safe way they read a file.

Every option that takes a value names one of these as its argparse `type`: a bad value is then
refused by argparse itself (`tools/NAME: error: argument --port: ...`, exit 2) before any work
starts. tests/tools/test_tool_options.py walks every tool's options with hostile values.

Files are read as tracer reads them: regular files only (a FIFO or a device is refused without
blocking on it), of bounded size, in one read of at most that size."""

from __future__ import annotations

import argparse
import math
import os
import pathlib
import stat
from collections.abc import Callable

MAX_TEXT_BYTES = 256 << 20  # a scene, a manifest, a job list: far above any real one


class UnreadableFile(Exception):
    """A file that is not a readable regular file of bounded size; the message says why."""


def read_regular_file(path: str | os.PathLike, limit: int = MAX_TEXT_BYTES) -> bytes:
    """The bytes of `path`, or UnreadableFile if it is not a regular file, is larger than `limit`
    or cannot be opened. Never blocks on a FIFO or a device, never reads more than `limit`."""
    try:
        descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY)
    except OSError as error:
        raise UnreadableFile(f"cannot open {os.fspath(path)}: {error.strerror}") from None
    info = os.fstat(descriptor)
    if not stat.S_ISREG(info.st_mode):
        os.close(descriptor)
        raise UnreadableFile(f"{os.fspath(path)} is not a regular file")
    with os.fdopen(descriptor, "rb") as file:
        if info.st_size > limit:
            raise UnreadableFile(f"{os.fspath(path)} holds {info.st_size:,} bytes, more than the {limit:,} allowed")
        data = file.read(limit + 1)
    if len(data) > limit:
        raise UnreadableFile(f"{os.fspath(path)} grew past the {limit:,} bytes allowed while it was read")
    return data


def read_text_file(path: str | os.PathLike, limit: int = MAX_TEXT_BYTES) -> str:
    """read_regular_file decoded as UTF-8 (UnreadableFile if it is not UTF-8)."""
    data = read_regular_file(path, limit)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise UnreadableFile(f"{os.fspath(path)} is not UTF-8 text (byte {error.start})") from None


def whole_number(low: int, high: int | None = None) -> Callable[[str], int]:
    """An argparse type: a whole number in [low, high] (high None: no upper bound)."""

    def parse(text: str) -> int:
        try:
            value = int(text, 10)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expects a whole number, found {text!r}") from None
        if value < low or (high is not None and value > high):
            bound = f"at least {low}" if high is None else f"between {low} and {high}"
            raise argparse.ArgumentTypeError(f"must be {bound}, found {value}")
        return value

    parse.__name__ = "whole number"
    return parse


def real_number(low: float, high: float | None = None, low_open: bool = False) -> Callable[[str], float]:
    """An argparse type: a finite number in [low, high] ((low, high] if low_open)."""

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expects a number, found {text!r}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"expects a finite number, found {text!r}")
        if value < low or (low_open and value == low) or (high is not None and value > high):
            lower = f"above {low:g}" if low_open else f"at least {low:g}"
            bound = lower if high is None else f"{lower} and at most {high:g}"
            raise argparse.ArgumentTypeError(f"must be {bound}, found {text}")  # low -inf: never reached
        return value

    parse.__name__ = "number"
    return parse


port = whole_number(0, 65535)
port.__doc__ = "An argparse type: a TCP port, 0 (any free one) to 65535."


def existing_file(text: str) -> pathlib.Path:
    """An argparse type: a path to an existing regular file (not read here)."""
    path = pathlib.Path(text)
    if not text:
        raise argparse.ArgumentTypeError("expects a file, found an empty path")
    try:
        info = path.stat()
    except OSError as error:
        raise argparse.ArgumentTypeError(f"cannot use {text}: {error.strerror}") from None
    if not stat.S_ISREG(info.st_mode):
        raise argparse.ArgumentTypeError(f"{text} is not a regular file")
    return path


def executable_file(text: str) -> str:
    """An argparse type: a program to run: an existing regular file this user may execute."""
    existing_file(text)
    if not os.access(text, os.X_OK):
        raise argparse.ArgumentTypeError(f"{text} is not executable")
    return text


def path_type(expects: str, problem: Callable[[pathlib.Path, str], str | None]) -> Callable[[str], pathlib.Path]:
    """An argparse type for a path: refuses the empty string ("expects EXPECTS") and any path for
    which problem(path, text) gives a reason."""

    def parse(text: str) -> pathlib.Path:
        if not text:
            raise argparse.ArgumentTypeError(f"expects {expects}, found an empty path")
        path = pathlib.Path(text)
        if reason := problem(path, text):
            raise argparse.ArgumentTypeError(reason)
        return path

    parse.__name__ = expects
    return parse


# The path types, each with the reason it refuses a path. Outputs may be missing (the tool makes
# their folder) but never a special file: the tool writes them whole, or not at all.
existing_folder = path_type("a folder", lambda path, text: None if path.is_dir() else f"{text} is not a folder")
existing_path = path_type("a path", lambda path, text: None if path.exists() else f"{text} does not exist")
output_file = path_type(
    "a file to write",
    lambda path, text: f"{text} exists and is not a regular file" if path.exists() and not path.is_file() else None,
)
output_folder = path_type(
    "a folder to write into",
    lambda path, text: f"{text} exists and is not a folder" if path.exists() and not path.is_dir() else None,
)
output_path = path_type(
    "a path to write",
    lambda path, text: f"{text} is neither a file nor a folder"
    if path.exists() and not (path.is_dir() or path.is_file())
    else None,
)


def split_passthrough(argv: list[str]) -> tuple[list[str], list[str]]:
    """A command line cut at its first `--`: the tool's own arguments, and those it passes on
    (to tracer, say) untouched."""
    if "--" not in argv:
        return argv, []
    cut = argv.index("--")
    return argv[:cut], argv[cut + 1 :]


def free_text(text: str) -> str:
    """An argparse type for values that are any text by nature (a commit, an address, a pattern):
    refuses only the empty string."""
    if not text:
        raise argparse.ArgumentTypeError("must not be empty")
    return text
