"""The language server's transport: JSON-RPC messages framed by Content-Length on stdin and
stdout, read strictly. Every request gets an answer: a message that is not JSON, or whose
params do not fit the method, is answered with JSON-RPC's error (-32700, -32600, -32602) instead
of being dropped. Framing that cannot be trusted any more (a header line that is not
`Name: value`, a Content-Length that is not a number or exceeds MAX_BODY_BYTES, input ending
inside a message) closes the connection with one line on stderr: after a wrong length no later
byte can be known to start a message."""

from __future__ import annotations

import asyncio
import json
import logging
import sys
import threading
from typing import BinaryIO

from pygls.exceptions import JsonRpcException
from pygls.io_ import StdoutWriter
from pygls.lsp.server import LanguageServer

MAX_HEADER_BYTES = 8192  # one header line
MAX_BODY_BYTES = 64 << 20  # one message: far above any scene an editor sends


class FramingError(Exception):
    """The input no longer follows the framing; the message says where it broke."""


def read_message(stream: BinaryIO) -> bytes | None:
    """The next message's body, or None where the input ends between messages."""
    length = None
    first = True
    while True:
        line = stream.readline(MAX_HEADER_BYTES + 1)
        if not line:
            if first:
                return None
            raise FramingError("the input ended inside a message's headers")
        first = False
        if not line.endswith(b"\r\n"):
            raise FramingError(f"a header line longer than {MAX_HEADER_BYTES} bytes or not ended by CRLF")
        if line == b"\r\n":
            break
        name, colon, value = line[:-2].partition(b":")
        if not colon:
            raise FramingError(f"a header line without ':': {line[:60]!r}")
        if name.strip().lower() == b"content-length":
            text = value.strip()
            if not text.isdigit() or int(text) > MAX_BODY_BYTES:
                raise FramingError(
                    f"Content-Length {text[:40].decode(errors='replace')!r} is not a length up to "
                    f"{MAX_BODY_BYTES} bytes"
                )
            length = int(text)
    if length is None:
        raise FramingError("a message without Content-Length")
    body = stream.read(length)
    if len(body) < length:
        raise FramingError("the input ended inside a message")
    return body


def answer_error(server: LanguageServer, message_id: object, code: int, text: str) -> None:
    """Sends JSON-RPC's error response to request `message_id` (null if it has no usable id)."""
    if not isinstance(message_id, (int, str)) or isinstance(message_id, bool):
        message_id = None
    body = json.dumps({"jsonrpc": "2.0", "id": message_id, "error": {"code": code, "message": text}})
    server.protocol.writer.write(f"Content-Length: {len(body.encode())}\r\n\r\n{body}".encode())


def handle_body(server: LanguageServer, body: bytes) -> None:
    """Decodes one message and hands it to the server's protocol, or answers with an error."""
    try:
        data = json.loads(body)
    except ValueError:  # not UTF-8, or not JSON
        return answer_error(server, None, -32700, "Parse error: the message is not JSON")
    if not isinstance(data, dict):
        return answer_error(server, None, -32600, "Invalid Request: a message is a JSON object")
    try:
        message = server.protocol.structure_message(data)
    except JsonRpcException as error:
        if "id" in data and "method" in data:  # a request: it must be answered
            answer_error(server, data["id"], error.code, f"{error.message} for {str(data['method'])[:80]}")
        return None
    server.protocol.handle_message(message)
    return None


async def serve(server: LanguageServer, stdin: BinaryIO) -> int:
    """Reads and dispatches messages until the input ends, framing breaks (exit 1) or the client
    says exit (pygls ends the process then)."""
    loop = asyncio.get_running_loop()
    while not server._stop_event.is_set():
        try:
            body = await loop.run_in_executor(server.thread_pool, read_message, stdin)
        except FramingError as error:
            print(f"tools/lsp: error: {error}; closing the connection", file=sys.stderr)
            return 1
        if body is None:
            return 0
        handle_body(server, body)
    return 0


class OneLineFormatter(logging.Formatter):
    """pygls's log records as one line each on stderr (the editor's log): their first line, no
    traceback (a malformed message is answered with an error; its traceback tells nothing more)."""

    def format(self, record: logging.LogRecord) -> str:
        first = record.getMessage().split("\n", 1)[0]
        return f"tools/lsp: {record.levelname.lower()}: {first}"


def serve_stdio(server: LanguageServer) -> int:
    """Serves on stdin and stdout; the exit code."""
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(OneLineFormatter())
    logging.basicConfig(level=logging.WARNING, handlers=[handler], force=True)
    server._stop_event = threading.Event()
    server.protocol.set_writer(StdoutWriter(sys.stdout.buffer))
    try:
        return asyncio.run(serve(server, sys.stdin.buffer))
    except BrokenPipeError:
        return 1
    except SystemExit as done:  # pygls's exit notification
        return done.code if isinstance(done.code, int) else 0
    finally:
        server.shutdown()
