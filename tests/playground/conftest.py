"""The playground (tools/playground) in Debian's headless Chromium, driven by Selenium: the site is
built once per run (the WebAssembly module and the page), served on 127.0.0.1, and each test opens
it in a fresh browser. Skipped, with the reason, where emscripten, Node.js, Chromium or its driver
is missing."""

import os
import pathlib
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))

from tracer_tools.playground import site  # noqa: E402

CHROMIUM = shutil.which("chromium")
CHROMEDRIVER = shutil.which("chromedriver")


def pytest_collection_modifyitems(items):
    missing = site.missing_tools()
    if not (CHROMIUM and CHROMEDRIVER):
        missing.append("Debian's chromium and chromium-driver")
    if missing:
        skip = pytest.mark.skip(
            reason="the playground's tests need " + ", ".join(missing) + " (tools/bootstrap --python installs them)"
        )
        for item in items:
            item.add_marker(skip)


@pytest.fixture(scope="session")
def tracer_bin():
    from tracer_tools.xcheck import ToolError, tracer_cli

    try:
        return tracer_cli.executable()  # $TRACER_BIN, else build/release/tracer
    except ToolError as error:
        pytest.fail(str(error))


@pytest.fixture(scope="session")
def site_folder(tmp_path_factory):
    """The site, built (tools/playground build) into a fresh folder."""
    folder = tmp_path_factory.mktemp("site")
    environment = dict(os.environ, PYTHONPATH=str(ROOT / "tools"))
    built = subprocess.run(
        [sys.executable, "-m", "tracer_tools", "playground", "build", "--out", str(folder), "-q"],
        env=environment,
        capture_output=True,
        text=True,
    )
    assert built.returncode == 0, built.stderr
    return folder


@pytest.fixture(scope="session")
def site_url(site_folder):
    server = site.BackgroundServer(site_folder)
    yield server.url
    server.stop()


@pytest.fixture
def own_server(site_folder):
    """A server of the site for one test alone (which may stop it)."""
    server = site.BackgroundServer(site_folder)
    yield server
    server.stop()


@pytest.fixture
def browser():
    driver = site.chromium(script_timeout=60)
    yield driver
    driver.quit()
