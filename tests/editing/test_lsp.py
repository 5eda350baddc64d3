"""The language server (tools/lsp) spoken to as an editor does: JSON-RPC over a real pipe,
initialize, didOpen, didChange with an error and with its fix, hover, completion, shutdown."""

import json
import os
import pathlib
import queue
import subprocess
import threading
import time
import urllib.parse

import pytest
from conftest import start_tool

SCENE = """let r = 0.5
material shiny { kd (1, 0.5, 0.2) ks 0.5 n 20 }
camera { eye (0, 0, 7) lookat (0, 0, 0) }
for i in 0..3 {
  sphere { center (i, 0, 0) radius r material shiny }
}
light { position (2, 3, 4) color 1 }
"""


class Client:
    """A minimal LSP client: Content-Length framed JSON-RPC on the server's stdin and stdout."""

    def __init__(self, tracer, *options):
        self.process = start_tool("lsp", *options, "--tracer", tracer, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.messages = queue.Queue()
        self.next_id = 0
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        stream = self.process.stdout
        while True:
            headers = {}
            while (line := stream.readline().decode()) not in ("\r\n", ""):
                name, _, value = line.partition(":")
                headers[name.strip().lower()] = value.strip()
            if not headers:
                return
            self.messages.put(json.loads(stream.read(int(headers["content-length"]))))

    def send(self, message):
        body = json.dumps(message).encode()
        self.process.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.process.stdin.flush()

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def request(self, method, params, timeout=30):
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": self.next_id, "method": method, "params": params})
        while True:
            message = self.messages.get(timeout=timeout)
            if message.get("id") == self.next_id and "method" not in message:
                assert "error" not in message, message
                return message["result"]

    def request_at(self, method, uri, text, needle, delta=0):
        """`method` at the place of `needle` (plus `delta` characters) in the document `text`."""
        return self.request(method, {"textDocument": {"uri": uri}, "position": position_of(text, needle, delta)})

    def diagnostics(self, uri, timeout=30):
        """The next diagnostics published for `uri`."""
        while True:
            message = self.messages.get(timeout=timeout)
            if message.get("method") == "textDocument/publishDiagnostics" and message["params"]["uri"] == uri:
                return message["params"]["diagnostics"]


def started(client):
    """`client` after the LSP's handshake."""
    result = client.request("initialize", {"processId": os.getpid(), "rootUri": None, "capabilities": {}})
    capabilities = result["capabilities"]
    assert capabilities["hoverProvider"]
    assert capabilities["completionProvider"]
    client.notify("initialized", {})
    return client


def stopped(client):
    assert client.request("shutdown", None) is None
    client.notify("exit", None)
    assert client.process.wait(timeout=10) == 0


@pytest.fixture
def client(tracer_bin):
    client = started(Client(tracer_bin))
    yield client
    stopped(client)


def position_of(text, needle, delta=0):
    before = text[: text.index(needle) + delta]
    return {"line": before.count("\n"), "character": len(before.rsplit("\n", 1)[-1])}


def open_document(client, tmp_path, text):
    uri = pathlib.Path(tmp_path / "scene.scn").as_uri()
    client.notify(
        "textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "tracer", "version": 1, "text": text}}
    )
    return uri


def change(client, uri, version, text):
    client.notify(
        "textDocument/didChange", {"textDocument": {"uri": uri, "version": version}, "contentChanges": [{"text": text}]}
    )


def test_diagnostics_follow_the_text_as_it_is_typed(client, tmp_path):
    uri = open_document(client, tmp_path, SCENE)
    assert client.diagnostics(uri) == []
    broken = SCENE.replace("radius r", "radius rr").replace("color 1", "colour 1")
    change(client, uri, 2, broken)
    found = client.diagnostics(uri)
    assert [d["message"] for d in found] == [
        "undefined name 'rr'",
        "unknown key 'colour' in light; did you mean 'color'?",
    ]
    assert found[0]["range"] == {"start": position_of(broken, "rr"), "end": position_of(broken, "rr", 2)}
    assert found[0]["severity"] == 1 and found[0]["source"] == "tracer"
    # The same messages as tracer --check gives in the terminal.
    check = subprocess.run(
        [client.process.args[-1], "--check", "--stdin-name", str(tmp_path / "scene.scn"), "-"],
        input=broken,
        capture_output=True,
        text=True,
    )
    for diagnostic in found:
        assert diagnostic["message"] in check.stderr
    # Two mistakes in one block, of two stages (a name, a key): both at once, not one per round.
    both = SCENE.replace("(i, 0, 0) radius r", "(ii, 0, 0) radus r")
    change(client, uri, 3, both)
    messages = [d["message"] for d in client.diagnostics(uri)]
    assert len(messages) == 2, messages
    assert messages[1].startswith("unknown key 'radus' in sphere; did you mean 'radius'?")
    assert messages[0] == "undefined name 'ii'"
    change(client, uri, 4, SCENE)
    assert client.diagnostics(uri) == []


def test_print_lines_are_shown_where_they_are_printed(client, tmp_path):
    uri = open_document(client, tmp_path, SCENE + 'print("r is", r)\n')
    found = client.diagnostics(uri)
    assert [d["message"] for d in found] == ["print: r is 0.5"]
    assert found[0]["severity"] == 3 and found[0]["range"]["start"]["line"] == SCENE.count("\n")


def test_an_error_in_an_included_file_is_published_for_that_file(client, tmp_path):
    (tmp_path / "lib.scn").write_text("let q = sqrt(-1)\n")
    uri = open_document(client, tmp_path, 'include "lib.scn"\n' + SCENE)
    lib = (tmp_path / "lib.scn").as_uri()
    while True:  # published for the scene (with nothing) and for lib.scn, in either order
        message = client.messages.get(timeout=30)
        if message.get("method") == "textDocument/publishDiagnostics" and message["params"]["uri"] == lib:
            assert message["params"]["diagnostics"][0]["range"]["start"]["line"] == 0
            break
    assert uri != lib


def test_hover_explains_keys_blocks_builtins_and_names(client, tmp_path):
    uri = open_document(client, tmp_path, SCENE)
    client.diagnostics(uri)

    def hover(needle, delta=1):
        result = client.request_at("textDocument/hover", uri, SCENE, needle, delta)
        return result["contents"]["value"] if result else None

    language = json.loads(
        subprocess.run([client.process.args[-1], "--language-json"], capture_output=True, text=True).stdout
    )
    sphere = next(b for b in language["blocks"] if b["kind"] == "sphere")
    radius = next(k for k in sphere["keys"] if k["name"] == "radius")
    assert radius["meaning"] in hover("radius r")
    assert sphere["summary"] in hover("sphere {")
    assert "for NAME in" in hover("for i")
    assert "defined at scene.scn:1" in hover("r material", 0)
    assert hover("\n}", 0) is None


def test_completion_offers_keys_blocks_materials_and_names_in_scope(client, tmp_path):
    uri = open_document(client, tmp_path, SCENE)
    client.diagnostics(uri)

    def labels(needle, delta=0):
        result = client.request_at("textDocument/completion", uri, SCENE, needle, delta)
        return {item["label"] for item in result["items"]}

    in_sphere = labels("radius r")
    assert {"center", "radius", "material", "r", "i", "shiny", "sqrt"} <= in_sphere
    assert "camera" not in in_sphere  # not a key of sphere
    top = labels("light {")
    assert {"camera", "sphere", "light", "let", "for", "r", "shiny"} <= top
    assert "i" not in top  # the loop variable is not in scope after its loop
    assert "radius" not in top


def test_a_newer_change_stops_the_check_of_an_older_one(client, tmp_path):
    import psutil

    uri = open_document(client, tmp_path, SCENE)
    client.diagnostics(uri)
    body = " ".join(f"let z{n} = k * {n}" for n in range(9))
    slow = SCENE + f"for k in 0..9000000 {{ {body} }}\n"  # seconds of work for tracer
    change(client, uri, 2, slow)
    server = psutil.Process(client.process.pid)
    deadline = time.monotonic() + 10
    while not [p for p in server.children() if "--stdin-name" in p.cmdline()]:
        assert time.monotonic() < deadline, "the slow check never started"
        time.sleep(0.02)
    change(client, uri, 3, SCENE.replace("radius r", "radius q"))
    assert [d["message"] for d in client.diagnostics(uri)] == ["undefined name 'q'"]
    time.sleep(0.2)
    assert not [
        p for p in server.children() if p.is_running() and p.status() != psutil.STATUS_ZOMBIE
    ], "the older check's tracer was stopped"


def test_go_to_definition_finds_the_name_in_scope(client, tmp_path):
    (tmp_path / "lib.scn").write_text("let k = 2\n")
    text = 'include "lib.scn"\n' + SCENE.replace("radius r", "radius r * k")
    uri = open_document(client, tmp_path, text)
    client.diagnostics(uri)

    def definition(needle, delta=0):
        return client.request_at("textDocument/definition", uri, text, needle, delta)

    assert definition("r * k") == {
        "uri": uri,
        "range": {"start": position_of(text, "r = 0.5"), "end": position_of(text, "r = 0.5", 1)},
    }
    assert definition("shiny }")["range"]["start"] == position_of(text, "shiny {")
    assert definition("i, 0, 0")["range"]["start"] == position_of(text, "i in")
    included = definition("k material")
    assert included["uri"] == (tmp_path / "lib.scn").as_uri()
    assert included["range"]["start"] == {"line": 0, "character": 4}
    assert definition("sphere {") is None  # a block kind, not a name


def test_an_assigned_name_leads_to_its_let_on_hover_and_definition(client, tmp_path):
    # `total = total + i` gives the outer name a new value: both uses are that `let`.
    text = SCENE + "let total = 0\nfor k in 0..4 {\n  total = total + k\n}\nprint(total)\n"
    uri = open_document(client, tmp_path, text)
    client.diagnostics(uri)
    for needle in ("total = total", "total + k", "total)"):
        found = client.request_at("textDocument/definition", uri, text, needle)
        assert found["range"]["start"] == position_of(text, "total = 0"), needle
        hover = client.request_at("textDocument/hover", uri, text, needle)
        assert hover["contents"]["value"].startswith("`total`: let, defined at scene.scn:"), hover


def test_go_to_definition_takes_the_inner_name_that_hides_an_outer_one(client, tmp_path):
    text = SCENE + "for j in 0..2 {\n  let r = j + 1\n  sphere { center (j, 2, 0) radius r / 9 material shiny }\n}\n"
    uri = open_document(client, tmp_path, text)
    assert client.diagnostics(uri) == []
    found = client.request_at("textDocument/definition", uri, text, "r / 9")
    assert found["range"]["start"] == position_of(text, "r = j")
    outer = client.request_at("textDocument/definition", uri, text, "r material")
    assert outer["range"]["start"] == position_of(text, "r = 0.5")


def test_a_standard_library_name_leads_to_a_read_only_copy_of_its_file(client, tmp_path, tracer_bin):
    text = 'include "std/colors.scn"\n' + SCENE.replace("color 1", "color tomato")
    uri = open_document(client, tmp_path, text)
    assert client.diagnostics(uri) == []
    found = client.request_at("textDocument/definition", uri, text, "tomato }")
    copy = pathlib.Path(urllib.parse.unquote(urllib.parse.urlparse(found["uri"]).path))
    library = json.loads(subprocess.run([tracer_bin, "--language-json"], capture_output=True, text=True).stdout)
    assert copy.name == "colors.scn" and copy.read_text() == library["library"]["std/colors.scn"]
    assert not os.access(copy, os.W_OK) or os.geteuid() == 0  # read-only (root may write anyway)
    assert not copy.stat().st_mode & 0o222
    lines = copy.read_text().splitlines()
    assert lines[found["range"]["start"]["line"]].startswith("let tomato = ")
    hover = client.request_at("textDocument/hover", uri, text, "tomato }")
    assert "colors.scn" in hover["contents"]["value"]


def test_include_folders_reach_tracer_and_the_copies_go_at_exit(tracer_bin, tmp_path, monkeypatch):
    for folder, name, value in (("one", "lib.scn", "let k = 2"), ("two", "more.scn", "let q = 3")):
        (tmp_path / folder).mkdir()
        (tmp_path / folder / name).write_text(value + "\n")
    monkeypatch.setenv("TRACER_PATH", str(tmp_path / "two"))  # the server's tracer inherits it
    client = started(Client(tracer_bin, "-I", tmp_path / "one"))
    scene = SCENE.replace("radius r material shiny", "radius r * k / q material glass")
    text = 'include "lib.scn"\ninclude "more.scn"\ninclude "std/materials.scn"\n' + scene.replace(
        "material shiny { kd (1, 0.5, 0.2) ks 0.5 n 20 }\n", ""
    )
    uri = open_document(client, tmp_path, text)
    assert client.diagnostics(uri) == []
    found = client.request_at("textDocument/definition", uri, text, "k / q")
    assert found["uri"] == (tmp_path / "one" / "lib.scn").as_uri()
    found = client.request_at("textDocument/definition", uri, text, "q material")
    assert found["uri"] == (tmp_path / "two" / "more.scn").as_uri()
    found = client.request_at("textDocument/definition", uri, text, "glass }")
    copy = pathlib.Path(urllib.parse.unquote(urllib.parse.urlparse(found["uri"]).path))
    assert copy.name == "materials.scn" and copy.exists()
    stopped(client)
    assert not copy.parent.parent.exists()  # the server's copies of the library, removed at its exit


def test_patterns_are_completed_after_their_keys_and_explained(client, tmp_path):
    text = SCENE + "plane { point (0, 0, 0) normal (0, 1, 0) material { kd checker { even 1 scale 0.5 } } }\n"
    uri = open_document(client, tmp_path, text)
    client.diagnostics(uri)
    after_kd = client.request_at("textDocument/completion", uri, text, "kd checker", 3)
    labels = {item["label"] for item in after_kd["items"]}
    assert {"checker", "marble", "image", "gradient"} <= labels  # patterns as kd's value
    inside = client.request_at("textDocument/completion", uri, text, "even 1", 0)
    assert {"even", "odd", "mapping", "scale"} <= {item["label"] for item in inside["items"]}
    hover = client.request_at("textDocument/hover", uri, text, "even 1", 1)
    assert "even" in hover["contents"]["value"] and "odd" not in {item["label"] for item in after_kd["items"]}
