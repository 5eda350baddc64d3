"""tools/preview's server without a browser: what it serves (the page, the state, the image),
on 127.0.0.1 only, and a clear refusal of a port already in use."""

import json
import signal
import socket
import subprocess
import time
import urllib.request

from conftest import start_preview, start_tool

SCENE = """camera { eye (0, 0, 7) lookat (0, 0, 0) }
render { width 50 height 30 }
sphere { center (0, 0, 0) radius 1 material { kd 1 } }
light { position (2, 3, 4) color 1 }
"""


def outward_address():
    """This machine's address on the interface toward other machines (no packet is sent), or None."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as udp:
        try:
            udp.connect(("192.0.2.123", 9))  # TEST-NET-1: routed like any outside address
        except OSError:
            return None
        address = udp.getsockname()[0]
    return None if address.startswith("127.") else address


def test_it_serves_the_page_the_state_and_the_image_on_localhost_only(tracer_bin, tmp_path):
    scene = tmp_path / "s.scn"
    scene.write_text(SCENE)
    process = start_preview(tracer_bin, scene, tmp_path / "out.png", 0)
    try:
        url = process.stdout.readline().split()[1]
        port = int(url.rsplit(":", 1)[1].strip("/"))
        assert url.startswith("http://127.0.0.1:")
        page = urllib.request.urlopen(url).read().decode()
        assert 'id="image"' in page and 'id="diagnostics"' in page
        deadline = time.monotonic() + 30
        while (state := json.loads(urllib.request.urlopen(url + "state").read()))["image_version"] == 0:
            assert time.monotonic() < deadline
            time.sleep(0.05)
        assert "50x30" in state["summary"] and state["diagnostics"] == ""
        image = urllib.request.urlopen(url + f"image?v={state['image_version']}").read()
        assert image[:4] == b"\x89PNG"
        address = outward_address()
        if address:  # another interface of this machine does not answer
            with socket.socket() as probe:
                probe.settimeout(1)
                assert probe.connect_ex((address, port)) != 0, address
    finally:
        process.send_signal(signal.SIGINT)
        assert process.wait(timeout=20) == 0


def test_a_port_in_use_is_refused_with_a_message(tracer_bin, tmp_path):
    scene = tmp_path / "s.scn"
    scene.write_text(SCENE)
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        process = start_preview(tracer_bin, scene, tmp_path / "out.png", taken.getsockname()[1])
        _, error = process.communicate(timeout=30)
    assert process.returncode == 3
    assert "cannot serve on 127.0.0.1:" in error and "try another --port" in error
    assert "Traceback" not in error


def test_the_documented_command_line_passes_options_after_dashes_to_tracer(tracer_bin, tmp_path):
    # docs/guide/editing.md: tools/preview my.scn -o OUT.png --port 0 -- --width 600
    scene = tmp_path / "my.scn"
    scene.write_text(SCENE)
    process = start_tool(
        "preview", scene, "-o", tmp_path / "OUT.png", "--port", "0", "--tracer", tracer_bin, "--", "--width", "40",
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        url = process.stdout.readline().split()[1]
        deadline = time.monotonic() + 30
        while (state := json.loads(urllib.request.urlopen(url + "state").read()))["image_version"] == 0:
            assert time.monotonic() < deadline
            time.sleep(0.05)
        assert "40x24" in state["summary"], state["summary"]
    finally:
        process.send_signal(signal.SIGINT)
        assert process.wait(timeout=20) == 0
