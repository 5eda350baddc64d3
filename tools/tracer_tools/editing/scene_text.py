"""What an editor needs to know about scene text around the cursor, without a parser: the
braces open at a place (and the block kind each belongs to), the word under the cursor, and
where a name defined at a place stops being visible. Comments (# to the end of the line) and
strings are skipped; tracer itself judges the text (tracer --check)."""

import re
from collections.abc import Iterator
from dataclasses import dataclass

WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


@dataclass
class Brace:
    offset: int  # of the '{'
    words: list[str]  # the words just before it, nearest last: ["material", "shiny"], ["sphere"]


def code_spans(text: str) -> Iterator[tuple[int, str]]:
    """(offset, character) for each character outside comments and strings."""
    in_string = False
    i = 0
    while i < len(text):
        c = text[i]
        if in_string:
            if c == '"' or c == "\n":
                in_string = False
        elif c == "#":
            end = text.find("\n", i)
            i = len(text) if end < 0 else end
            continue
        elif c == '"':
            in_string = True
        else:
            yield i, c
        i += 1


def words_before(text: str, offset: int, most: int = 3) -> list[str]:
    """The last `most` words (and ')' as a word) before `offset`, nearest last."""
    found = re.findall(r"[A-Za-z_][A-Za-z0-9_]*|\)|\.\.|[0-9.]+", text[max(0, offset - 200) : offset])
    return found[-most:]


def open_braces(text: str, offset: int) -> list[Brace]:
    """The braces still open at `offset`, outermost first."""
    stack: list[Brace] = []
    for i, c in code_spans(text[:offset]):
        if c == "{":
            stack.append(Brace(i, words_before(text, i)))
        elif c == "}" and stack:
            stack.pop()
    return stack


def matching_close(text: str, open_offset: int) -> int:
    """The offset of the '}' closing the '{' at `open_offset` (the text's end if none)."""
    depth = 0
    for i, c in code_spans(text[open_offset:]):
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                return open_offset + i
    return len(text)


def next_open_brace(text: str, offset: int) -> int | None:
    """The first '{' at or after `offset`, outside comments and strings."""
    for i, c in code_spans(text[offset:]):
        if c == "{":
            return offset + i
    return None


def visible_range(text: str, offset: int, kind: str) -> tuple[int, int]:
    """Where a name defined at `offset` can be used: a loop variable or a parameter in the
    braces that follow it; any other name from its definition to the end of the braces around it."""
    if kind in ("for", "parameter"):
        brace = next_open_brace(text, offset)
        if brace is None:
            return offset, offset
        return brace, matching_close(text, brace)
    around = open_braces(text, offset)
    return offset, matching_close(text, around[-1].offset) if around else len(text)


def word_at(text: str, offset: int) -> tuple[str, int] | None:
    """The word under `offset` (or just before it) and where it starts."""
    for match in WORD.finditer(text, max(0, offset - 100), min(len(text), offset + 100)):
        if match.start() <= offset <= match.end():
            return match.group(), match.start()
    return None


def block_kind(brace: Brace, kinds: set[str]) -> str | None:
    """The block kind a '{' opens (`sphere {`, `material shiny {`, `material {` after a key), or None
    for the braces of statements (for, if, fn, group)."""
    words = brace.words
    if words and words[-1] in kinds:
        return words[-1]
    if len(words) >= 2 and words[-2] in kinds and WORD.fullmatch(words[-1]):
        return words[-2]  # a named block
    return None


def line_offsets(text: str) -> list[int]:
    """The offset at which each line starts."""
    starts = [0]
    for i, c in enumerate(text):
        if c == "\n":
            starts.append(i + 1)
    return starts
