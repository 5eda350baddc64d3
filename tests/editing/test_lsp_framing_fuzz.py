"""The language server's transport (tools/tracer_tools/editing/lsp_io.py) fuzzed with Hypothesis:
any byte stream is read as messages or ends in FramingError, never another exception, never a
read past MAX_BODY_BYTES; any message body is handed on or answered with an error response, and
every request that cannot be handed on gets exactly one answer. CI runs a few hundred streams;
TRACER_FUZZ_EXAMPLES sets how many (the 10-minute run in the issue's note used 10^6)."""

import io
import json
import os

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pygls.exceptions import JsonRpcInvalidParams

from tracer_tools.editing import lsp_io

EXAMPLES = int(os.environ.get("TRACER_FUZZ_EXAMPLES", "300"))
FUZZ = settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=list(HealthCheck))

json_values = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=20),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4),
    max_leaves=12,
)
messages = st.fixed_dictionaries(
    {"jsonrpc": st.sampled_from(["2.0", "1.0"])},
    optional={
        "id": st.integers() | st.text(max_size=8) | st.none() | json_values,
        "method": st.sampled_from(["textDocument/hover", "textDocument/completion", "initialize", "x"]) | st.text(),
        "params": json_values,
    },
)


def framed(body: bytes) -> bytes:
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


pieces = st.one_of(
    messages.map(lambda m: framed(json.dumps(m).encode())),
    st.binary(max_size=64).map(framed),
    st.binary(max_size=64),
    st.sampled_from(
        [b"\r\n", b"Content-Length: abc\r\n", b"Content-Length: -1\r\n\r\n", b"Content-Length: 99999999999\r\n"]
    ),
)


@FUZZ
@given(st.lists(pieces, max_size=8))
def test_any_stream_is_messages_then_at_most_one_framing_error(parts):
    stream = io.BytesIO(b"".join(parts))
    for _ in range(100):
        try:
            body = lsp_io.read_message(stream)
        except lsp_io.FramingError:
            return
        if body is None:
            return
        assert len(body) <= lsp_io.MAX_BODY_BYTES


class Writer:
    def __init__(self):
        self.sent = []

    def write(self, data: bytes):
        header, _, body = data.partition(b"\r\n\r\n")
        assert header.startswith(b"Content-Length: ") and int(header[16:]) == len(body)
        self.sent.append(json.loads(body))


class Protocol:
    """Stands for pygls's protocol: structures like it for the methods it knows, records what it
    is handed."""

    def __init__(self):
        self.writer = Writer()
        self.handled = []

    def structure_message(self, data):
        if data.get("jsonrpc") != "2.0" or not isinstance(data.get("params", {}), dict):
            raise JsonRpcInvalidParams()
        return data

    def handle_message(self, message):
        self.handled.append(message)


class Server:
    def __init__(self):
        self.protocol = Protocol()


@FUZZ
@given(st.one_of(messages.map(lambda m: json.dumps(m).encode()), st.binary(max_size=64)))
def test_every_body_is_handed_on_or_answered(body):
    server = Server()
    lsp_io.handle_body(server, body)
    handled, sent = server.protocol.handled, server.protocol.writer.sent
    assert len(handled) + len(sent) <= 1
    try:
        data = json.loads(body)
    except ValueError:
        assert sent[0]["error"]["code"] == -32700
        return
    if not isinstance(data, dict):
        assert sent[0]["error"]["code"] == -32600
    elif handled:
        assert handled[0] == data
    elif "id" in data and "method" in data:
        assert sent[0]["error"]["code"] == -32602  # a request that is not handed on is answered
        assert (
            sent[0]["id"] == data["id"]
            if isinstance(data["id"], (int, str)) and not isinstance(data["id"], bool)
            else sent[0]["id"] is None
        )
