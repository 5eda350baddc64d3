"""tools/playground: builds tracer's browser playground into a folder any static host serves, and
serves that folder on this machine.

  tools/playground build [--out DIR]     the WebAssembly module (emscripten, src/web), the page
                                         (playground/: CodeMirror 6 from its lockfile, bundled by
                                         esbuild) and the gallery (scenes/), into DIR
                                         (default build/web/site)
  tools/playground serve [--port N]      serves DIR on 127.0.0.1 (port 0: any free one; the address
                                         is printed) until Ctrl-C"""

import argparse
import functools
import gzip
import http.server
import os
import pathlib
import shutil
import subprocess
import sys
import threading

from tracer_tools import ROOT, option_types

MODULE_DIR = ROOT / "build" / "web"
SITE_DIR = MODULE_DIR / "site"
PAGE_DIR = ROOT / "playground"
TOOLCHAIN = pathlib.Path("/usr/share/emscripten/cmake/Modules/Platform/Emscripten.cmake")
# Debian's emscripten runs its JavaScript passes with `node`, which finds Debian's node modules
# (acorn) only on this path when the machine's node is not Debian's own.
NODE_PATH = "/usr/share/nodejs"


class PlaygroundError(Exception):
    """What stops a build or a server, said in one line."""


# How Debian's Chromium runs headless here: no sandbox (root), no GPU, and no connections of its
# own (a closed network refuses them, many at a time).
CHROMIUM_ARGUMENTS = (
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-dev-shm-usage",
    "--disable-background-networking",
    "--disable-component-update",
    "--no-first-run",
)


def chromium(script_timeout: float) -> object:
    """Debian's Chromium, headless, driven by Selenium through chromium-driver (the tests' and the
    benchmark's browser)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium")
    for argument in CHROMIUM_ARGUMENTS:
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=options)
    driver.set_script_timeout(script_timeout)
    return driver


def missing_tools() -> list[str]:
    """The programs a build needs that this machine lacks, each with what provides it."""
    wanted = {"emcmake": "Debian's emscripten", "node": "Node.js", "npm": "npm"}
    missing = [f"{name} ({source})" for name, source in wanted.items() if not shutil.which(name)]
    if shutil.which("emcmake") and not TOOLCHAIN.exists():
        missing.append(f"{TOOLCHAIN} (Debian's emscripten)")
    return missing


def run(command: list[str], cwd: pathlib.Path, quiet: bool) -> None:
    """Runs `command`, raising PlaygroundError with its last lines if it fails."""
    environment = dict(os.environ, NODE_PATH=os.pathsep.join(filter(None, [NODE_PATH, os.environ.get("NODE_PATH")])))
    result = subprocess.run(command, cwd=cwd, env=environment, capture_output=quiet, text=True)
    if result.returncode != 0:
        tail = "\n".join(((result.stdout or "") + (result.stderr or "")).strip().splitlines()[-15:])
        raise PlaygroundError(f"{' '.join(command)} failed (exit {result.returncode})" + (f":\n{tail}" if tail else ""))


def build_module(quiet: bool) -> None:
    """The WebAssembly module: src/web built by emscripten's CMake into build/web."""
    if not (MODULE_DIR / "build.ninja").exists():
        run(
            [
                "cmake",
                "-S",
                str(ROOT),
                "-B",
                str(MODULE_DIR),
                "-G",
                "Ninja",
                f"-DCMAKE_TOOLCHAIN_FILE={TOOLCHAIN}",
                "-DCMAKE_BUILD_TYPE=Release",
            ],
            ROOT,
            quiet,
        )
    run(["cmake", "--build", str(MODULE_DIR), "--target", "tracer_web"], ROOT, quiet)


def build_page(out: pathlib.Path, quiet: bool) -> None:
    """The page: its packages as the lockfile pins them (installed again when it changes), bundled."""
    stamp = PAGE_DIR / "node_modules" / ".package-lock.json"
    lockfile = PAGE_DIR / "package-lock.json"
    if not stamp.exists() or stamp.stat().st_mtime < lockfile.stat().st_mtime:
        run(["npm", "ci", "--no-audit", "--no-fund", "--loglevel=error"], PAGE_DIR, quiet)
    run(["node", "build.mjs", str(MODULE_DIR), str(out)], PAGE_DIR, quiet)


def site_sizes(folder: pathlib.Path) -> dict[str, int]:
    """Each file's size in the folder, gzip-compressed (what a static host sends), in bytes."""
    return {path.name: len(gzip.compress(path.read_bytes(), 9)) for path in sorted(folder.iterdir()) if path.is_file()}


def build(arguments: argparse.Namespace) -> int:
    missing = missing_tools()
    if missing:
        raise PlaygroundError(
            "cannot build the playground without " + ", ".join(missing) + " (tools/bootstrap --python installs them)"
        )
    out = pathlib.Path(arguments.out).resolve()
    build_module(arguments.quiet)
    build_page(out, arguments.quiet)
    if not arguments.quiet:
        sizes = site_sizes(out)
        print(
            f"tools/playground: the site is in {out} ({sum(sizes.values()) / 1e6:.2f} MB compressed)", file=sys.stderr
        )
    return 0


class SiteHandler(http.server.SimpleHTTPRequestHandler):
    """The site's files, WebAssembly with its own type, and no request lines on the terminal."""

    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".wasm": "application/wasm",
        ".js": "text/javascript",
    }

    def log_message(self, *args: object) -> None:
        pass


def site_server(folder: str | os.PathLike, port: int = 0) -> http.server.ThreadingHTTPServer:
    """A server of the site in `folder` on 127.0.0.1:`port` (0: one the system picks), bound but not
    yet serving; OSError if the port cannot be had."""
    return http.server.ThreadingHTTPServer(("127.0.0.1", port), functools.partial(SiteHandler, directory=str(folder)))


class BackgroundServer:
    """The site in `folder` served from a thread of its own on a port the system picked (`url`),
    until stop(): the tests' and the benchmark's server."""

    def __init__(self, folder: str | os.PathLike):
        self.server = site_server(folder)
        threading.Thread(target=self.server.serve_forever, daemon=True).start()
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}/"

    def stop(self) -> None:
        self.server.shutdown()
        self.server.server_close()


def serve(arguments: argparse.Namespace) -> int:
    folder = pathlib.Path(arguments.folder).resolve()
    if not (folder / "index.html").exists():
        raise PlaygroundError(f"{folder} holds no site: build it first (tools/playground build)")
    try:
        server = site_server(folder, arguments.port)
    except OSError as error:
        raise PlaygroundError(f"cannot serve on port {arguments.port}: {error.strerror}") from None
    print(f"tools/playground: http://127.0.0.1:{server.server_address[1]}/", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(prog="tools/playground", description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    building = commands.add_parser("build", help="build the site")
    building.add_argument(
        "--out",
        type=option_types.output_folder,
        default=str(SITE_DIR),
        help="the site's folder (default build/web/site)",
    )
    building.add_argument("-q", "--quiet", action="store_true", help="print only errors")
    serving = commands.add_parser("serve", help="serve the site on 127.0.0.1")
    serving.add_argument(
        "--port", type=option_types.port, default=8000, help="the port (0: any free one; default 8000)"
    )
    serving.add_argument(
        "--folder",
        type=option_types.output_path,
        default=str(SITE_DIR),
        help="the site's folder (default build/web/site)",
    )
    arguments = parser.parse_args()
    try:
        return build(arguments) if arguments.command == "build" else serve(arguments)
    except PlaygroundError as error:
        print(f"tools/playground: error: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
