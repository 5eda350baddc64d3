"""tools/lsp: tracer's language server, over stdio. It publishes tracer's own diagnostics as
the user types (tracer --check --diagnostics json on the unsaved text, under the file's name, so
that includes and meshes are found beside it), explains keys, blocks and built-ins on hover
(tracer --language-json: the same tables as the reference) and completes block kinds, keys,
material names and the names in scope.

Names from tracer's standard library (include "std/...", built into tracer) are shown from copies
of its files the server writes, read-only, into a temporary folder.

Usage: tools/lsp [--tracer build/release/tracer] [-I DIR ...]  (an editor starts it; see
docs/editing.md)"""

import argparse
import asyncio
import atexit
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import urllib.parse

from lsprotocol import types
from pygls.lsp.server import LanguageServer

from tracer_tools import ROOT, option_types
from tracer_tools.editing import lsp_io, scene_text
from tracer_tools.editing.language import Entry, Language

# A check starts this long after the last keystroke (one run per pause, not per key).
CHECK_DELAY = 0.15
# A check still running after this long (a scene that loops for minutes) is stopped.
CHECK_TIMEOUT = 30.0
# How tracer names a file of its standard library in messages (built in: no such file on disk).
LIBRARY_PREFIX = "<std>/"
# A file the editor has not opened (an included one) is read only if regular and at most this long.
MAX_UNOPENED_BYTES = 16 << 20
# Completion offers at most this many items at once (marked incomplete past it).
MAX_COMPLETIONS = 1000
MAX_PRINTS_SHOWN = 100  # of a scene's print(...) lines, as information at their place

SEVERITY = {
    "error": types.DiagnosticSeverity.Error,
    "warning": types.DiagnosticSeverity.Warning,
    "note": types.DiagnosticSeverity.Information,
}
COMPLETION_KIND = {
    "block": types.CompletionItemKind.Class,
    "key": types.CompletionItemKind.Property,
    "statement": types.CompletionItemKind.Keyword,
    "word": types.CompletionItemKind.Keyword,
    "function": types.CompletionItemKind.Function,
    "constant": types.CompletionItemKind.Constant,
    "let": types.CompletionItemKind.Variable,
    "param": types.CompletionItemKind.Variable,
    "for": types.CompletionItemKind.Variable,
    "parameter": types.CompletionItemKind.Variable,
    "fn": types.CompletionItemKind.Function,
    "shape": types.CompletionItemKind.Struct,
    "material": types.CompletionItemKind.Reference,
}


def uri_to_path(uri: str) -> str:
    return urllib.parse.unquote(urllib.parse.urlparse(uri).path)


def path_to_uri(path: str) -> str:
    return pathlib.Path(os.path.abspath(path)).as_uri()


def read_unopened(path: str) -> str:
    """The text of a file the editor has not opened: "" unless a regular file of bounded size."""
    try:
        return option_types.read_regular_file(path, MAX_UNOPENED_BYTES).decode(errors="replace")
    except option_types.UnreadableFile:
        return ""


def utf16_column(line: str, byte_column: int) -> int:
    """The LSP character (UTF-16 units) of tracer's 1-based byte column on `line`."""
    prefix = line.encode()[: max(byte_column - 1, 0)].decode(errors="ignore")
    return len(prefix.encode("utf-16-le")) // 2


def offset_of(text: str, position: types.Position) -> int:
    """The string offset of an LSP position."""
    starts = scene_text.line_offsets(text)
    line = min(position.line, len(starts) - 1)
    start = starts[line]
    end = starts[line + 1] - 1 if line + 1 < len(starts) else len(text)
    units = 0
    for i, c in enumerate(text[start:end]):
        if units >= position.character:
            return start + i
        units += 2 if ord(c) > 0xFFFF else 1
    return end


class TracerServer(LanguageServer):
    def __init__(self, tracer: str, include_dirs: tuple[str, ...] = ()):
        super().__init__("tracer-lsp", "1")
        self.tracer = tracer
        self.include_dirs = include_dirs  # given to tracer as -I (TRACER_PATH reaches it by the environment)
        self.language = Language.from_tracer(tracer)
        self.library_folder: str | None = None  # where the standard library's files are copied, once
        self.pending: dict[str, asyncio.Task] = {}
        self.names: dict[str, list[dict]] = {}  # by document: the names of its last check
        self.published: dict[str, set[str]] = {}  # by document: the URIs given diagnostics

    def document_source(self, uri: str) -> str:
        """The text of an open document, else of the regular file behind the URI (bounded; "" if
        it is not one: a FIFO or a device is never opened for reading)."""
        if (document := self.workspace.text_documents.get(uri)) is not None:
            return document.source
        return read_unopened(uri_to_path(uri))

    def library_file(self, path: str) -> str:
        """A file of tracer's standard library ("<std>/colors.scn") as a read-only copy editors can open;
        `path` itself if it names none."""
        text = (
            self.language.library.get("std/" + path[len(LIBRARY_PREFIX) :]) if path.startswith(LIBRARY_PREFIX) else None
        )
        if text is None:
            return path
        if self.library_folder is None:
            self.library_folder = tempfile.mkdtemp(prefix="tracer-lsp-")
            atexit.register(shutil.rmtree, self.library_folder, True)
        target = pathlib.Path(self.library_folder, "std", path[len(LIBRARY_PREFIX) :])
        if not target.exists():
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(text)
            target.chmod(0o444)
        return str(target)

    def with_library_files(self, value: object) -> object:
        """tracer's report with every "path" of a library file replaced by its copy's."""
        if isinstance(value, dict):
            return {
                key: self.library_file(item)
                if key == "path" and isinstance(item, str)
                else self.with_library_files(item)
                for key, item in value.items()
            }
        if isinstance(value, list):
            return [self.with_library_files(item) for item in value]
        return value

    async def check(self, uri: str) -> None:
        """Runs tracer on the document's text and publishes what it says, by file."""
        source = self.document_source(uri)
        path = uri_to_path(uri)
        process = await asyncio.create_subprocess_exec(
            self.tracer,
            "--check",
            "--diagnostics",
            "json",
            "--stdin-name",
            path,
            *(argument for folder in self.include_dirs for argument in ("-I", folder)),
            "-",
            stdin=asyncio.subprocess.PIPE,
            stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.PIPE,
        )
        try:  # a newer change cancels this check: its tracer is stopped, not left running
            out, _ = await asyncio.wait_for(process.communicate(source.encode()), CHECK_TIMEOUT)
        except asyncio.CancelledError:
            process.kill()
            await process.wait()
            raise
        except asyncio.TimeoutError:
            process.kill()
            await process.wait()
            return
        try:
            report = self.with_library_files(json.loads(out.decode().splitlines()[0]))
        except (IndexError, ValueError):
            return
        if report["names"] or report["ok"]:
            self.names[uri] = report["names"]
        by_uri: dict[str, list[types.Diagnostic]] = {}
        for found in report["diagnostics"]:
            target = uri if found["path"] == path else path_to_uri(found["path"])
            by_uri.setdefault(target, []).append(self.lsp_diagnostic(found))
        for line in report.get("prints", [])[:MAX_PRINTS_SHOWN]:  # what print(...) wrote, at its line
            target = uri if line["path"] == path else path_to_uri(line["path"])
            by_uri.setdefault(target, []).append(
                types.Diagnostic(
                    range=self.lsp_range(line),
                    message="print: " + line["text"],
                    source="tracer",
                    severity=types.DiagnosticSeverity.Information,
                )
            )
        for target in self.published.get(uri, set()) - set(by_uri):
            by_uri[target] = []  # cleared
        self.published[uri] = {target for target, items in by_uri.items() if items}
        by_uri.setdefault(uri, [])
        for target, items in by_uri.items():
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(uri=target, diagnostics=items))

    def lsp_range(self, found: dict) -> types.Range:
        """The LSP range of a diagnostic of tracer's JSON (the whole first line's start for a whole file)."""
        line = max(found["line"] - 1, 0)
        text = self.line_text(found["path"], line)
        start = utf16_column(text, found["column"]) if found["line"] > 0 else 0
        end = start + max(found["length"], 1) if found["line"] > 0 else 0
        return types.Range(types.Position(line, start), types.Position(line, end))

    def line_text(self, path: str, line: int) -> str:
        """Line `line` (from 0) of `path`: the open document's text if open, else the file's ("" if unreadable)."""
        document = self.workspace.text_documents.get(path_to_uri(path))
        lines = document.lines if document else read_unopened(path).splitlines()
        return lines[line] if line < len(lines) else ""

    def lsp_diagnostic(self, found: dict) -> types.Diagnostic:
        """A diagnostic of tracer's JSON as the LSP's, its notes as related information."""
        related = [
            types.DiagnosticRelatedInformation(
                location=types.Location(uri=path_to_uri(note["path"]), range=self.lsp_range(note)),
                message=note["message"],
            )
            for note in found["notes"]
        ]
        message = found["message"]
        if found["repeats"]:
            message += f" (and {found['repeats']} more times at this place)"
        return types.Diagnostic(
            range=self.lsp_range(found),
            message=message,
            source="tracer",
            severity=SEVERITY[found["severity"]],
            related_information=related or None,
        )

    def schedule_check(self, uri: str) -> None:
        """Checks the document CHECK_DELAY after now, cancelling a check scheduled or running."""
        if task := self.pending.get(uri):
            task.cancel()

        async def later():
            await asyncio.sleep(CHECK_DELAY)
            await self.check(uri)

        self.pending[uri] = asyncio.ensure_future(later())

    # Hover and completion.
    def context_kind(self, text: str, offset: int) -> str | None:
        """The block kind whose braces hold `offset`, or None at the top level or in statements."""
        braces = scene_text.open_braces(text, offset)
        return scene_text.block_kind(braces[-1], set(self.language.blocks)) if braces else None

    def scene_names(self, uri: str, text: str, offset: int) -> list[dict]:
        """The names of the last check visible at `offset` (material names everywhere)."""
        path = uri_to_path(uri)
        starts = scene_text.line_offsets(text)
        braces = scene_text.BraceMap(text)
        visible = []
        for name in self.names.get(uri, []):
            if name["kind"] == "material" or name["path"] != path:
                visible.append(name)
                continue
            line = name["line"] - 1
            if line >= len(starts):
                continue
            line_end = starts[line + 1] if line + 1 < len(starts) else len(text)
            line_text = text[starts[line] : line_end]
            if line_text.isascii():  # a byte column is a character column
                column = min(name["column"] - 1, len(line_text))
            else:
                column = len(line_text.encode()[: name["column"] - 1].decode(errors="ignore"))
            begin, end = braces.visible_range(starts[line] + column, name["kind"])
            if begin <= offset <= end:
                visible.append(name)
        return visible

    def hover_entry(self, uri: str, text: str, offset: int) -> Entry | None:
        """What the word at `offset` is: a key of the enclosing block, a block kind, a built-in or a scene name."""
        found = scene_text.word_at(text, offset)
        if not found:
            return None
        word, start = found
        kind = self.context_kind(text, start)
        if kind and (entry := self.language.key_entry(kind, word)):
            return entry
        if word in self.language.blocks:
            return self.language.block_entry(word)
        if word in self.language.words:
            return self.language.words[word]
        for name in self.scene_names(uri, text, offset):
            if name["name"] == word:
                where = f"{pathlib.Path(name['path']).name}:{name['line']}"
                return Entry(word, name["kind"], name["kind"], f"`{word}`: {name['kind']}, defined at {where}")
        return None

    def definition(self, uri: str, text: str, offset: int) -> types.Location | None:
        """Where the scene name at `offset` is defined: of the definitions in scope there, the last
        one written before it (an inner `let` hides an outer one), else any (a material, an include's)."""
        found = scene_text.word_at(text, offset)
        if not found:
            return None
        named = [n for n in self.scene_names(uri, text, offset) if n["name"] == found[0]]
        if not named:
            return None
        path = uri_to_path(uri)
        here = text[:offset].count("\n") + 1
        before = [n for n in named if n["path"] == path and n["line"] <= here]
        chosen = max(before, key=lambda n: (n["line"], n["column"])) if before else named[0]
        line = chosen["line"] - 1
        start = utf16_column(self.line_text(chosen["path"], line), chosen["column"])
        end = start + len(found[0].encode("utf-16-le")) // 2
        return types.Location(
            uri=path_to_uri(chosen["path"]), range=types.Range(types.Position(line, start), types.Position(line, end))
        )

    def completions(self, uri: str, text: str, offset: int) -> types.CompletionList:
        """What may be written at `offset`: keys in a block, else blocks and statements; built-ins;
        names in scope. Only those that start with the word being typed, and at most
        MAX_COMPLETIONS (then marked incomplete: the editor asks again as the word grows)."""
        kind = self.context_kind(text, offset)
        typed = scene_text.word_before(text, offset)
        entries: list[Entry] = []
        if kind:
            entries += self.language.keys(kind)
            # After a key that takes a pattern (`kd ch`): the patterns, as values.
            before = scene_text.words_before(text, offset - len(typed), 1)
            if before and self.language.key_takes_pattern(kind, before[-1]):
                entries += [self.language.block_entry(k) for k in self.language.patterns]
        else:
            entries += [self.language.block_entry(k) for k in self.language.top_level]
            entries += [e for e in self.language.words.values() if e.kind == "statement"]
        entries += [e for e in self.language.words.values() if e.kind in ("function", "constant", "word")]
        items = [
            types.CompletionItem(
                label=e.label,
                kind=COMPLETION_KIND[e.kind],
                detail=e.detail,
                documentation=types.MarkupContent(types.MarkupKind.Markdown, e.documentation),
            )
            for e in entries
            if e.label.startswith(typed)
        ]
        seen = {item.label for item in items}
        file_names: dict[str, str] = {}  # path -> its last part, once per file
        for name in self.scene_names(uri, text, offset):
            label = name["name"]
            if label in seen or not label.startswith(typed):
                continue
            if len(items) == MAX_COMPLETIONS:
                return types.CompletionList(is_incomplete=True, items=items)
            seen.add(label)
            file_name = file_names.get(name["path"]) or file_names.setdefault(
                name["path"], pathlib.Path(name["path"]).name
            )
            items.append(
                types.CompletionItem(
                    label=label,
                    kind=COMPLETION_KIND[name["kind"]],
                    detail=f"{name['kind']} ({file_name}:{name['line']})",
                )
            )
        return types.CompletionList(is_incomplete=False, items=items)


def make_server(tracer: str, include_dirs: tuple[str, ...] = ()) -> TracerServer:
    """The server with its handlers, checking with the tracer executable at `tracer`."""
    server = TracerServer(tracer, include_dirs)

    @server.feature(types.TEXT_DOCUMENT_DID_OPEN)
    async def did_open(ls: TracerServer, params: types.DidOpenTextDocumentParams):
        await ls.check(params.text_document.uri)

    @server.feature(types.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: TracerServer, params: types.DidChangeTextDocumentParams):
        ls.schedule_check(params.text_document.uri)

    @server.feature(types.TEXT_DOCUMENT_DID_SAVE)
    async def did_save(ls: TracerServer, params: types.DidSaveTextDocumentParams):
        await ls.check(params.text_document.uri)

    @server.feature(types.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: TracerServer, params: types.DidCloseTextDocumentParams):
        ls.names.pop(params.text_document.uri, None)

    @server.feature(types.TEXT_DOCUMENT_HOVER)
    def hover(ls: TracerServer, params: types.HoverParams):
        source = ls.document_source(params.text_document.uri)
        offset = offset_of(source, params.position)
        entry = ls.hover_entry(params.text_document.uri, source, offset)
        if entry is None:
            return None
        return types.Hover(contents=types.MarkupContent(types.MarkupKind.Markdown, entry.documentation))

    @server.feature(types.TEXT_DOCUMENT_DEFINITION)
    def definition(ls: TracerServer, params: types.DefinitionParams):
        source = ls.document_source(params.text_document.uri)
        return ls.definition(params.text_document.uri, source, offset_of(source, params.position))

    @server.feature(types.TEXT_DOCUMENT_COMPLETION, types.CompletionOptions(trigger_characters=[" "]))
    def completion(ls: TracerServer, params: types.CompletionParams):
        source = ls.document_source(params.text_document.uri)
        return ls.completions(params.text_document.uri, source, offset_of(source, params.position))

    return server


def main() -> int:
    """tools/lsp: serves on stdin and stdout until the client says exit."""
    parser = argparse.ArgumentParser(prog="tools/lsp", description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--tracer",
        type=option_types.executable_file,
        default=str(ROOT / "build" / "release" / "tracer"),
        help="the tracer executable (default: %(default)s)",
    )
    parser.add_argument(
        "-I",
        "--include-dir",
        action="append",
        default=[],
        type=option_types.existing_folder,
        help="a folder tracer looks for included files in (tracer -I); repeatable, in order",
    )
    args = parser.parse_args()
    try:
        server = make_server(args.tracer, tuple(str(folder) for folder in args.include_dir))
    except (OSError, ValueError, subprocess.SubprocessError) as error:
        print(f"tools/lsp: error: {args.tracer} --language-json gave no language tables: {error}", file=sys.stderr)
        return 1
    return lsp_io.serve_stdio(server)
