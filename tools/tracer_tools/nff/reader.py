"""Reads an NFF file into entities, checking every number; errors carry file:line:col.

NFF is a stream of whitespace-separated words: an entity's numbers may run on over several lines
(upstream's generators write `c` on one line or three). `#` starts a comment to the end of the line.
"""

from __future__ import annotations

import dataclasses
import math
import pathlib
import re
from collections.abc import Iterator
from typing import Never

MAX_POLYGON_CORNERS = 100_000  # as tracer's OBJ reader (src/io/obj_reader.h), and ...
MAX_POLYGON_WORK = 2e10  # ... the sum of n^2 over polygons of 5+ corners: Earcut's worst case stays ~30 s
MAX_ERRORS = 20


class NffError(Exception):
    """Errors in an NFF file, each already formatted `file:line:col: error: ...` with its line and a caret."""

    def __init__(self, messages: list[str]) -> None:
        super().__init__("\n".join(messages))
        self.messages = messages


@dataclasses.dataclass
class Word:
    text: str
    line: int  # 1-based
    column: int  # 1-based, in characters (bytes: the file is read as Latin-1)
    line_start: int  # offset of its line in the text


@dataclasses.dataclass
class View:
    eye: tuple
    lookat: tuple
    up: tuple
    angle: float
    hither: float
    resolution: tuple
    word: Word


@dataclasses.dataclass
class Light:
    position: tuple
    color: tuple | None  # None: not given (NFF leaves the intensity to the program)
    word: Word


@dataclasses.dataclass
class Fill:
    """An `f` line: colour, Kd, Ks (highlight and mirror weight), Phong power, T, index of refraction."""

    color: tuple
    kd: float
    ks: float
    shine: float
    t: float
    ior: float


@dataclasses.dataclass
class Sphere:
    center: tuple
    radius: float
    fill: Fill
    word: Word


@dataclasses.dataclass
class Cone:
    base: tuple
    base_radius: float
    apex: tuple
    apex_radius: float
    fill: Fill
    word: Word


@dataclasses.dataclass
class Polygon:
    points: list
    normals: list | None  # per corner for a `pp` patch
    fill: Fill
    word: Word


@dataclasses.dataclass
class Scene:
    path: str
    view: View | None = None
    background: tuple = (0.0, 0.0, 0.0)
    lights: list = dataclasses.field(default_factory=list)
    warnings: list = dataclasses.field(default_factory=list)
    source: object = None  # the _Source: source.diagnostic(kind, word, message) formats a message at a word


_TOKENS = re.compile(r"(\r\n|\r|\n)|#[^\r\n]*|([^\s#]+)")
_WINDOW = 160  # characters of a long line shown around the column


def _words(text: str, end: list[int]) -> Iterator[Word]:
    """Every word of the text with its line and column, lazily (comments dropped); at the end,
    end[0] and end[1] are the last line's number and start offset (the last line that has text,
    when the file ends with a line break)."""
    line, line_start, previous_start = 1, 0, 0
    for match in _TOKENS.finditer(text):
        if match.group(1):
            line, line_start, previous_start = line + 1, match.end(), line_start
        elif match.group(2):
            yield Word(match.group(2), line, match.start() - line_start + 1, line_start)
    end[:] = [line - 1, previous_start] if line > 1 and line_start == len(text) else [line, line_start]


class _Source:
    """The file's words with a one-word lookahead, and the formatting of diagnostics at a word.
    Words are made as they are read: memory holds the text and the scene, not a list of words."""

    def __init__(self, path: str, text: str) -> None:
        self.path = path
        self.text = text
        self.end = [1, 0]
        self.words = _words(text, self.end)
        self.ahead = next(self.words, None)

    def diagnostic(self, kind: str, word: Word | None, message: str) -> str:
        if word is None:  # the end of the file
            line, line_start = self.end
            line_text = self.line_at(line_start)
            column = len(line_text) + 1
        else:
            line, column, line_start = word.line, word.column, word.line_start
            line_text = self.line_at(line_start)
        first = max(0, column - 1 - _WINDOW // 2) if len(line_text) > _WINDOW else 0
        shown = "".join(c if c.isprintable() else "?" for c in line_text[first : first + _WINDOW])
        caret = " " * min(column - 1 - first, len(shown)) + "^"
        return f"{self.path}:{line}:{column}: {kind}: {message}\n  {shown}\n  {caret}"

    def line_at(self, start: int) -> str:
        ends = [i for i in (self.text.find("\n", start), self.text.find("\r", start)) if i >= 0]
        return self.text[start : min(ends) if ends else len(self.text)]

    def at_end(self):
        return self.ahead is None

    def peek(self):
        return self.ahead

    def take(self):
        word = self.ahead
        self.ahead = next(self.words, None)
        return word


class _Abandon(Exception):
    """Stops reading an entity whose words are wrong (the error is already recorded)."""


class _Reader:
    def __init__(self, path: str, text: str, sink: object) -> None:
        self.source = _Source(path, text)
        self.scene = Scene(path, source=self.source)
        self.sink = sink
        self.errors = []
        self.fill = None
        self.polygon_work = 0.0

    # --- words -------------------------------------------------------------------------
    def error(self, word: Word | None, message: str) -> Never:
        self.errors.append(self.source.diagnostic("error", word, message))
        raise _Abandon

    def warning(self, word: Word, message: str) -> None:
        if len(self.scene.warnings) < MAX_ERRORS:  # as many warnings as errors are shown
            self.scene.warnings.append(self.source.diagnostic("warning", word, message))

    def number(self, what: str) -> float:
        word = self.source.take()
        if word is None:
            self.error(None, f"expected {what}, found the end of the file")
        try:
            value = float(word.text.replace("_", " "))  # Python's float() would read 1_000
        except ValueError:
            self.error(word, f"expected {what}, found '{word.text}'")
        if not math.isfinite(value) or abs(value) > 1e30:
            self.error(word, f"{what} must be a finite number within ±1e30, found '{word.text}'")
        return value

    def vector(self, what: str) -> tuple[float, float, float]:
        return tuple(self.number(f"{what} ({axis})") for axis in "xyz")

    def count(self, what: str, least: int, most: int) -> int:
        word = self.source.peek()
        value = self.number(what)
        if value != int(value) or not least <= value <= most:
            self.error(word, f"{what} must be a whole number from {least} to {most:,}, found '{word.text}'")
        return int(value)

    def keyword(self, expected: str) -> None:
        word = self.source.take()
        if word is None:
            self.error(None, f"expected '{expected}', found the end of the file")
        if word.text != expected:
            self.error(word, f"expected '{expected}', found '{word.text}'")

    # --- entities ----------------------------------------------------------------------
    def read(self):
        handlers = {
            "v": self.view,
            "b": self.background,
            "l": self.light,
            "f": self.fill_line,
            "c": self.cone,
            "s": self.sphere,
            "p": self.polygon,
            "pp": self.polygon,
        }
        while not self.source.at_end() and len(self.errors) < MAX_ERRORS:
            word = self.source.take()
            handler = handlers.get(word.text)
            try:
                if handler is None:
                    self.error(word, f"unknown NFF entity '{word.text}' (expected one of v, b, l, f, c, s, p, pp)")
                handler(word)
            except _Abandon:
                self.skip_to_entity()
        if self.scene.view is None and not self.errors:
            self.errors.append(self.source.diagnostic("error", None, "no view ('v' entity): NFF requires one"))
        if self.errors:
            if len(self.errors) >= MAX_ERRORS:
                self.errors.append(f"{self.source.path}: note: stopped after {MAX_ERRORS} errors")
            raise NffError(self.errors)
        return self.scene

    def skip_to_entity(self) -> None:
        """After an error, resumes at the next word that starts a line and names an entity."""
        entities = {"v", "b", "l", "f", "c", "s", "p", "pp"}
        while not self.source.at_end():
            word = self.source.peek()
            if word.column == 1 and word.text in entities:
                return
            self.source.take()

    def view(self, word: Word) -> None:
        if self.scene.view is not None:
            self.error(word, "a second view: NFF has one 'v' per file")
        fields = {}
        for name, read in (
            ("from", lambda: self.vector("the eye position")),
            ("at", lambda: self.vector("the point looked at")),
            ("up", lambda: self.vector("the up vector")),
            ("angle", lambda: self.number("the view angle in degrees")),
            ("hither", lambda: self.number("the hither distance")),
            ("resolution", lambda: (self.count("the width", 2, 16384), self.count("the height", 2, 16384))),
        ):
            self.keyword(name)
            fields[name] = read()
        if not 0 < fields["angle"] < 180:
            self.error(word, f"the view angle must be between 0 and 180 degrees, found {fields['angle']:g}")
        self.scene.view = View(
            fields["from"], fields["at"], fields["up"], fields["angle"], fields["hither"], fields["resolution"], word
        )

    def colour(self, what: str) -> tuple[float, float, float]:
        word = self.source.peek()
        value = tuple(self.number(f"{what} ({channel})") for channel in ("red", "green", "blue"))
        if min(value) < 0:
            self.error(word, f"{what} must not be negative")
        return value

    def background(self, word: Word) -> None:
        self.scene.background = self.colour("the background colour")

    def light(self, word: Word) -> None:
        position = self.vector("the light position")
        color = None
        following = self.source.peek()
        if following is not None and following.line == word.line and self._is_number(following.text):
            color = self.colour("the light colour")
        self.scene.lights.append(Light(position, color, word))

    @staticmethod
    def _is_number(text: str) -> bool:
        try:
            float(text)
        except ValueError:
            return False
        return True

    def fill_line(self, word: Word) -> None:
        color = self.colour("the colour")
        names = ("Kd", "Ks", "the Phong power", "T (transmittance)")
        kd, ks, shine, t = (self.number(name) for name in names)
        ior = self.number("the index of refraction")
        self.fill = Fill(color, kd, ks, shine, t, ior)  # kept if refused below: no error per shape after it
        for name, value in zip(names, (kd, ks, shine, t), strict=True):
            if value < 0:
                self.error(word, f"{name} must not be negative, found {value:g}")
        # Ks is also the mirror weight (tracer's km) and T the transmitted one (kt): at most 1 each,
        # as tracer requires (docs/decisions.md), or products along a ray grow without bound.
        for name, value in (("Ks (the mirror weight)", ks), ("T (transmittance)", t)):
            if value > 1:
                self.error(word, f"{name} must be at most 1, found {value:g}")
        if t > 0 and ior <= 0:
            self.error(word, f"a transmitting surface (T {t:g}) needs an index of refraction > 0, found {ior:g}")

    def current_fill(self, word: Word) -> Fill:
        if self.scene.view is None:
            self.error(word, "a shape before the view: NFF defines the view ('v') first")
        if self.fill is None:
            self.error(word, "a shape before any 'f' line: its surface is not defined")
        return self.fill

    def emit(self, method: str, shape: Sphere | Cone | Polygon) -> None:
        """Hands a shape to the sink (sink.sphere, .cone or .polygon), unless errors were found
        (nothing will be written then)."""
        if not self.errors:
            try:
                method(self.scene, shape)
            except TooManyMaterials as error:
                self.error(*error.args)

    def sphere(self, word: Word) -> None:
        fill = self.current_fill(word)
        center = self.vector("the sphere's centre")
        radius_word = self.source.peek()
        radius = self.number("the sphere's radius")
        if radius == 0:
            self.error(radius_word, "a sphere of radius 0")
        if radius < 0:
            self.warning(radius_word, "negative radius (inside visible only): drawn two-sided like every shape")
        self.emit(self.sink.sphere, Sphere(center, abs(radius), fill, word))

    def cone(self, word: Word) -> None:
        fill = self.current_fill(word)
        base = self.vector("the base centre")
        base_radius = self.number("the base radius")
        apex = self.vector("the apex centre")
        radius_word = self.source.peek()
        apex_radius = self.number("the apex radius")
        if base == apex:
            self.error(word, "the base and apex of a cone are the same point")
        if base_radius < 0 and apex_radius < 0:
            self.warning(word, "negative radii (inside visible only): drawn two-sided like every shape")
            base_radius, apex_radius = -base_radius, -apex_radius
        if base_radius < 0 or apex_radius < 0 or base_radius == apex_radius == 0:
            self.error(radius_word, "a cone's radii must both be positive (or both negative), one may be 0")
        self.emit(self.sink.cone, Cone(base, base_radius, apex, apex_radius, fill, word))

    def polygon(self, word: Word) -> None:
        fill = self.current_fill(word)
        patch = word.text == "pp"
        corners = self.count("the number of corners", 3, MAX_POLYGON_CORNERS)
        if corners >= 5:
            self.polygon_work += corners * corners
            if self.polygon_work > MAX_POLYGON_WORK:
                self.error(
                    word,
                    "the polygons are too large in all (the sum of their squared corner counts "
                    f"passes {MAX_POLYGON_WORK:g}); split them into smaller ones",
                )
        points, normals = [], [] if patch else None
        for index in range(corners):
            points.append(self.vector(f"corner {index + 1}"))
            if patch:
                normals.append(self.vector(f"the normal at corner {index + 1}"))
        self.emit(self.sink.polygon, Polygon(points, normals, fill, word))


class TooManyMaterials(Exception):
    """Raised by a sink with (word, message) when a shape brings one material too many."""


def read_nff(path: str | pathlib.Path, text: str, sink: object) -> Scene:
    """Reads NFF `text` (from `path`, named in diagnostics), handing each shape to the sink as
    it is read (sink.sphere / .cone / .polygon (scene, shape)); returns the Scene (view,
    background, lights, warnings). Raises NffError with every error found (at most 20)."""
    return _Reader(str(path), text, sink).read()
