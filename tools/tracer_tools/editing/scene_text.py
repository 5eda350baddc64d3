"""What an editor needs to know about scene text around the cursor, without a parser: the
braces open at a place (and the block kind each belongs to), the word under the cursor, and
where a name defined at a place stops being visible. Comments (# to the end of the line) and
strings are skipped; tracer itself judges the text (tracer --check)."""

import bisect
import re
from collections.abc import Iterator
from dataclasses import dataclass

WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
NEWLINE = re.compile("\n")


@dataclass
class Brace:
    offset: int  # of the '{'
    words: list[str]  # the words just before it, nearest last: ["material", "shiny"], ["sphere"]


# A comment (to the end of its line), a string (to its closing quote or the end of its line) or
# a brace: the scans below take the braces and step over the rest in one match each.
BRACE_OR_SKIPPED = re.compile(r'#[^\n]*|"[^"\n]*"?|[{}]')


def braces(text: str, end: int | None = None) -> Iterator[tuple[int, str]]:
    """(offset, '{' or '}') for each brace before `end` outside comments and strings."""
    for match in BRACE_OR_SKIPPED.finditer(text, 0, len(text) if end is None else end):
        c = match.group()
        if c == "{" or c == "}":
            yield match.start(), c


def words_before(text: str, offset: int, most: int = 3) -> list[str]:
    """The last `most` words (and ')' as a word) before `offset`, nearest last."""
    found = re.findall(r"[A-Za-z_][A-Za-z0-9_]*|\)|\.\.|[0-9.]+", text[max(0, offset - 200) : offset])
    return found[-most:]


def open_braces(text: str, offset: int) -> list[Brace]:
    """The braces still open at `offset`, outermost first."""
    stack: list[Brace] = []
    for i, c in braces(text, offset):
        if c == "{":
            stack.append(Brace(i, words_before(text, i)))
        elif c == "}" and stack:
            stack.pop()
    return stack


class BraceMap:
    """Every brace pair of a text, found in one pass, for the questions asked once per name
    (where a name stays visible): each in O(log n), so that a document's thousands of names cost
    about one pass over it, not one each."""

    def __init__(self, text: str):
        self.end = len(text)
        self.opens: list[int] = []  # every '{' outside comments and strings, in order
        self.close_of: dict[int, int] = {}  # '{' -> its '}' (the text's end if unclosed)
        self.events: list[int] = []  # offsets of the braces, in order
        self.innermost: list[int] = []  # the innermost '{' open just after each event (-1: none)
        stack: list[int] = []
        for i, c in braces(text):
            if c == "{":
                stack.append(i)
                self.opens.append(i)
            elif stack:
                self.close_of[stack.pop()] = i
            else:
                continue
            self.events.append(i)
            self.innermost.append(stack[-1] if stack else -1)
        for left in stack:
            self.close_of[left] = self.end

    def enclosing(self, offset: int) -> int:
        """The innermost '{' open at `offset` (after the characters before it), or -1."""
        k = bisect.bisect_left(self.events, offset) - 1
        return self.innermost[k] if k >= 0 else -1

    def visible_range(self, offset: int, kind: str) -> tuple[int, int]:
        """Where a name defined at `offset` can be used: a loop variable or a parameter in the
        braces that follow it; any other name from its definition to the end of the braces
        around it."""
        if kind in ("for", "parameter"):
            k = bisect.bisect_left(self.opens, offset)
            if k == len(self.opens):
                return offset, offset
            return self.opens[k], self.close_of[self.opens[k]]
        around = self.enclosing(offset)
        return offset, self.close_of[around] if around >= 0 else self.end


def word_at(text: str, offset: int) -> tuple[str, int] | None:
    """The word under `offset` (or just before it) and where it starts."""
    for match in WORD.finditer(text, max(0, offset - 100), min(len(text), offset + 100)):
        if match.start() <= offset <= match.end():
            return match.group(), match.start()
    return None


def word_before(text: str, offset: int) -> str:
    """The part of a word that ends at `offset` (what is being typed), or ""."""
    start = offset
    while start > 0 and offset - start < 100 and (text[start - 1].isalnum() or text[start - 1] == "_"):
        start -= 1
    return text[start:offset] if WORD.fullmatch(text[start:offset]) else ""


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
    return [0, *(match.end() for match in NEWLINE.finditer(text))]
