"""The language server (tools/lsp) against a client that misbehaves, over a real pipe: every
request is answered (an error response where its params are invalid), files the editor has not
opened are read only if regular and bounded, broken framing closes the connection with one
line, and completion over thousands of names stays one pass over the document."""

import os
import pathlib
import queue
import subprocess

import pytest
from conftest import start_tool
from test_lsp import Client, open_document


class RawClient(Client):
    def __init__(self, tracer):
        self.process = start_tool(
            "lsp", "--tracer", tracer, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE
        )
        self.messages = queue.Queue()
        self.next_id = 0
        import threading

        threading.Thread(target=self._read, daemon=True).start()

    def answer(self, method, params, timeout=30):
        """The whole response to a request (result or error)."""
        self.next_id += 1
        self.send({"jsonrpc": "2.0", "id": self.next_id, "method": method, "params": params})
        while True:
            message = self.messages.get(timeout=timeout)
            if message.get("id") == self.next_id and "method" not in message:
                return message


@pytest.fixture
def raw(tracer_bin):
    client = RawClient(tracer_bin)
    assert "result" in client.answer("initialize", {"processId": os.getpid(), "rootUri": None, "capabilities": {}})
    client.notify("initialized", {})
    yield client
    client.process.kill()
    client.process.wait(timeout=10)


def hover(client, uri, line=0, character=0):
    return client.answer(
        "textDocument/hover", {"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}
    )


def test_unopened_fifos_and_devices_are_never_read(raw, tmp_path):
    fifo = tmp_path / "pipe.scn"
    os.mkfifo(fifo)
    assert hover(raw, fifo.as_uri()) == {"jsonrpc": "2.0", "id": raw.next_id, "result": None}
    assert hover(raw, "file:///dev/zero")["result"] is None
    assert hover(raw, (tmp_path / "missing.scn").as_uri())["result"] is None
    regular = tmp_path / "closed.scn"
    regular.write_text("sphere { center (0, 0, 0) radius 1 }\n")
    assert "sphere" in hover(raw, regular.as_uri(), 0, 2)["result"]["contents"]["value"]


@pytest.mark.parametrize("line,character", [(-5, 0), (0, -5), (2**40, 0), ("x", 0)])
def test_a_request_with_invalid_params_gets_an_error_response(raw, tmp_path, line, character):
    uri = open_document(raw, tmp_path, "let r = 1\n")
    answer = hover(raw, uri, line, character)
    assert answer["error"]["code"] == -32602, answer
    assert hover(raw, uri, 0, 1)["result"] is not None  # `let`  # still serving


def test_a_message_that_is_not_json_gets_a_parse_error_and_the_server_goes_on(raw, tmp_path):
    raw.process.stdin.write(b"Content-Length: 5\r\n\r\n{oops")
    raw.process.stdin.flush()
    assert raw.messages.get(timeout=30) == {
        "jsonrpc": "2.0",
        "id": None,
        "error": {"code": -32700, "message": "Parse error: the message is not JSON"},
    }
    raw.process.stdin.write(b"Content-Length: 2\r\n\r\n[]")
    raw.process.stdin.flush()
    assert raw.messages.get(timeout=30)["error"]["code"] == -32600
    uri = open_document(raw, tmp_path, "let r = 1\n")
    assert hover(raw, uri, 0, 1)["result"] is not None  # `let`


@pytest.mark.parametrize(
    "frame",
    [b"Content-Length: abc\r\n\r\n{}", b"Content-Length: 99999999999\r\n\r\n", b"no colon here\r\n\r\n", b"\r\n"],
)
def test_broken_framing_closes_the_connection_with_one_line(raw, frame):
    raw.process.stdin.write(frame)
    raw.process.stdin.flush()
    assert raw.process.wait(timeout=30) == 1
    error = raw.process.stderr.read().decode()
    assert "tools/lsp: error:" in error and "closing the connection" in error
    assert "Traceback" not in error


def test_completion_over_thousands_of_names_is_bounded_and_marked_incomplete(raw, tmp_path):
    text = "".join(f"let v{i} = {i}\n" for i in range(5000)) + "camera { eye (0, 0, 7) lookat (0, 0, 0) }\n"
    uri = open_document(raw, tmp_path, text)
    raw.diagnostics(uri, timeout=60)
    everything = raw.answer(
        "textDocument/completion", {"textDocument": {"uri": uri}, "position": {"line": 5001, "character": 0}}
    )
    assert everything["result"]["isIncomplete"] is True
    assert len(everything["result"]["items"]) == 1000
    typed = raw.answer(
        "textDocument/completion", {"textDocument": {"uri": uri}, "position": {"line": 4999, "character": 7}}
    )
    labels = {item["label"] for item in typed["result"]["items"]}  # "let v49" typed: v49, v490..v499, v4900..
    assert typed["result"]["isIncomplete"] is False
    assert "v49" in labels and "v4999" in labels and "v5" not in labels and "sphere" not in labels


def test_a_tracer_that_gives_no_tables_is_one_line_and_exit_1(tmp_path):
    fake = tmp_path / "fake"
    fake.write_text("#!/bin/sh\necho not json\n")
    fake.chmod(0o755)
    process = start_tool(
        "lsp", "--tracer", fake, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )
    _, error = process.communicate(timeout=30)
    assert process.returncode == 1
    assert "gave no language tables" in error.decode() and "Traceback" not in error.decode()
    assert pathlib.Path(fake).exists()
