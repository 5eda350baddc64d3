"""tools/preview: a page in the browser that shows the scene's latest image while you edit it.

It runs `tracer SCENE -o OUT --watch --diagnostics json` and serves, on 127.0.0.1 only, a page
that refreshes by itself: the image after each save (a quick preview, then the full one), the
render's summary line, or, when the scene has errors, tracer's diagnostics as the terminal
shows them (file:line:col, the source line, the caret), above the last good image.

Usage: tools/preview SCENE [-o OUT.png] [--port N] [--tracer PATH] [-- TRACER OPTIONS]"""

import argparse
import html
import http.server
import json
import pathlib
import signal
import subprocess
import sys
import threading

from tracer_tools import ROOT, option_types

PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>tracer: {title}</title>
<style>
 body {{ font-family: sans-serif; margin: 1em; background: #222; color: #ddd; }}
 #image {{ max-width: 100%; image-rendering: pixelated; background: #000; }}
 #diagnostics {{ color: #f88; background: #111; padding: 0.5em; white-space: pre; overflow-x: auto; }}
 #diagnostics:empty {{ display: none; }}
 #summary {{ font-family: monospace; color: #aaa; }}
</style></head>
<body>
<h1 id="scene">{title}</h1>
<pre id="diagnostics"></pre>
<p id="summary">waiting for the first image...</p>
<img id="image" alt="the rendered image">
<script>
let shown = -1;
async function refresh() {{
  try {{
    const state = await (await fetch("state", {{cache: "no-store"}})).json();
    document.getElementById("diagnostics").textContent = state.diagnostics;
    document.getElementById("summary").textContent = state.summary;
    if (state.image_version !== shown && state.image_version > 0) {{
      const image = document.getElementById("image");
      image.width = state.full_width;
      image.src = "image?v=" + state.image_version;
      image.dataset.version = state.image_version;
      image.dataset.stage = state.stage;
      shown = state.image_version;
    }}
    document.body.dataset.loads = state.loads;
  }} catch (error) {{
    document.getElementById("summary").textContent = "the preview server stopped";
  }}
  setTimeout(refresh, 200);
}}
refresh();
</script>
</body></html>
"""


class PreviewState:
    """What the page shows, updated from tracer's events."""

    def __init__(self, output: pathlib.Path):
        self.lock = threading.Lock()
        self.output = output
        self.image = b""
        self.state = {
            "image_version": 0,
            "stage": "",
            "summary": "waiting for the first image...",
            "diagnostics": "",
            "full_width": 0,
            "loads": 0,
        }

    def on_event(self, event: dict) -> None:
        """Takes one event of tracer --watch --diagnostics json into the page's state."""
        with self.lock:
            if event["event"] == "load":
                self.state["loads"] += 1
                self.state["diagnostics"] = event["text"]
                if not event["ok"]:
                    self.state["summary"] = "the scene has errors; the last good image is shown"
            elif event["event"] == "image":
                self.image = self.output.read_bytes()
                self.state.update(
                    image_version=self.state["image_version"] + 1,
                    stage=event["stage"],
                    full_width=event["full_width"],
                    summary=event["summary"] + (" (preview)" if event["stage"] == "preview" else ""),
                )
            elif event["event"] == "error":
                self.state["diagnostics"] = "tracer: error: " + event["message"]

    def snapshot(self) -> tuple[dict, bytes]:
        """The page's state and the latest image's bytes, read together."""
        with self.lock:
            return dict(self.state), self.image


def make_handler(state: PreviewState, title: str) -> type:
    """The HTTP handler class: / (the page), /state (JSON), /image (the PNG)."""
    page = PAGE.format(title=html.escape(title)).encode()

    class Handler(http.server.BaseHTTPRequestHandler):
        def do_GET(self) -> None:  # noqa: N802 (the name http.server calls)
            path = self.path.split("?")[0]
            if path == "/":
                self.reply(200, "text/html; charset=utf-8", page)
            elif path == "/state":
                self.reply(200, "application/json", json.dumps(state.snapshot()[0]).encode())
            elif path == "/image" and state.snapshot()[1]:
                self.reply(200, "image/png", state.snapshot()[1])
            else:
                self.reply(404, "text/plain", b"not found")

        def reply(self, code: int, content_type: str, body: bytes) -> None:
            self.send_response(code)
            self.send_header("Content-Type", content_type)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, *args: object) -> None:
            pass  # quiet

    return Handler


def follow(process: subprocess.Popen, state: PreviewState) -> None:
    """Feeds tracer's events to `state` until tracer ends."""
    for line in process.stdout:
        state.on_event(json.loads(line))


def stop_on_sigterm(*_: object) -> None:
    """SIGTERM stops the server as Ctrl-C does (tracer is then stopped too)."""
    raise KeyboardInterrupt


def main() -> int:
    """tools/preview: serves until Ctrl-C or SIGTERM, then stops tracer."""
    parser = argparse.ArgumentParser(
        prog="tools/preview",
        description=__doc__.split("\n\n")[0],
        usage="tools/preview [-h] [-o OUTPUT] [--port PORT] [--tracer TRACER] scene [-- TRACER_OPTION...]",
    )
    parser.add_argument("scene", type=option_types.free_text, help="the scene file to watch")
    parser.add_argument(
        "-o", "--output", type=option_types.output_file, help="the image tracer writes (default: out/preview/SCENE.png)"
    )
    parser.add_argument(
        "--port", type=option_types.port, default=8000, help="the local port (0: any free one; default 8000)"
    )
    parser.add_argument(
        "--tracer", type=option_types.executable_file, default=str(ROOT / "build" / "release" / "tracer")
    )
    own, tracer_options = option_types.split_passthrough(sys.argv[1:])
    args = parser.parse_args(own)
    scene = pathlib.Path(args.scene)
    output = args.output or ROOT / "out" / "preview" / (scene.stem + ".png")
    if output.suffix.lower() != ".png":
        parser.error("the preview page shows PNG images: give -o NAME.png")
    try:
        output.parent.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        parser.error(f"cannot make the folder of {output}: {error.strerror}")
    state = PreviewState(output)
    try:
        server = http.server.ThreadingHTTPServer(("127.0.0.1", args.port), make_handler(state, str(scene)))
    except OSError as error:
        print(
            f"tools/preview: error: cannot serve on 127.0.0.1:{args.port}: {error.strerror}; try another --port "
            "(0: any free one)",
            file=sys.stderr,
        )
        return 3
    process = subprocess.Popen(
        [args.tracer, str(scene), "-o", str(output), "--watch", "--diagnostics", "json", *tracer_options],
        stdout=subprocess.PIPE,
        text=True,
    )
    threading.Thread(target=follow, args=(process, state), daemon=True).start()
    signal.signal(signal.SIGTERM, stop_on_sigterm)
    print(
        f"tools/preview: http://127.0.0.1:{server.server_address[1]}/ (Ctrl-C stops); the image: {output}", flush=True
    )
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        process.terminate()
        process.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
