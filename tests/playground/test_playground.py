"""The playground in a real browser: typing a scene shows its image, the same pixels as the command
line's; a mistake shows tracer's diagnostic at its line and column and keeps the last good image;
fixing it renders again; gallery scenes with a mesh and with a picture render as the command line
renders them; a share link carries the text; an edit during a long render drops that render."""

import subprocess

import pytest
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import WebDriverWait

ROOT = __import__("pathlib").Path(__file__).resolve().parents[2]
WAIT = 120  # seconds: a busy machine's slowest render, never a measure of speed

SMALL = """render {{ width 96 height 64 }}
camera {{ eye (0, 0, 7) lookat (0, 0, 0) fovy 40 }}
sphere {{ center (0, 0, 0) radius 1.5 material {{ ka 0.1 kd {colour} ks 0.5 n 30 }} }}
plane {{ point (0, -1.5, 0) normal (0, 1, 0) material {{ kd 0.6 km 0.3 }} }}
light {{ position (3, 4, 5) color 1 }}
"""


def page_state(browser):
    return browser.execute_script(
        "const c = document.getElementById('image'); const p = window.tracerPlayground;"
        "return {version: +c.dataset.version, final: c.dataset.final === 'true', job: +(c.dataset.job || 0),"
        " jobs: p ? p.jobs() : 0, sent: !!p && p.jobText() === p.view.state.doc.toString(),"
        " status: document.getElementById('status').textContent,"
        " diagnostics: document.getElementById('diagnostics').textContent}"
    )


def open_page(browser, url):
    browser.get(url)
    WebDriverWait(browser, WAIT).until(lambda b: b.execute_script("return !!window.tracerPlayground"))
    WebDriverWait(browser, WAIT).until(lambda b: page_state(b)["final"])  # the default scene's image


def set_text(browser, text):
    browser.execute_script(
        "const v = window.tracerPlayground.view;"
        "v.dispatch({changes: {from: 0, to: v.state.doc.length, insert: arguments[0]}});",
        text,
    )


def wait_for_final_of_latest(browser):
    """The page's state once the latest edit's whole image is drawn, or its diagnostics shown."""

    def done(b):
        state = page_state(b)
        if not state["sent"]:  # the edit not yet sent to the worker (typing pauses first)
            return None
        return state if (state["final"] and state["job"] == state["jobs"]) or state["diagnostics"] else None

    return WebDriverWait(browser, WAIT).until(done)


def canvas_rgb(browser):
    """The canvas's pixels as RGB bytes, row by row from the top, and its size."""
    width, height, data = browser.execute_script(
        "const c = document.getElementById('image');"
        "const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
        "let s = ''; for (let i = 0; i < d.length; i += 4) s += String.fromCharCode(d[i], d[i+1], d[i+2]);"
        "return [c.width, c.height, btoa(s)];"
    )
    import base64

    return width, height, base64.b64decode(data)


def native_rgb(tracer_bin, tmp_path, scene_text=None, scene_path=None):
    """The command line's 8-bit pixels of the scene (text written beside the gallery, or a file)."""
    if scene_text is not None:
        scene_path = tmp_path / "scene.scn"
        scene_path.write_text(scene_text)
    out = tmp_path / "native.ppm"
    subprocess.run([tracer_bin, str(scene_path), "-o", str(out), "-q"], check=True, timeout=300)
    data = out.read_bytes()
    magic, size, _, pixels = data.split(b"\n", 3)
    width, height = map(int, size.split())
    return width, height, pixels


def test_typing_a_scene_shows_its_image_with_the_native_pixels(site_url, browser, tracer_bin, tmp_path):
    open_page(browser, site_url)
    editor = browser.find_element(By.CSS_SELECTOR, ".cm-content")
    set_text(browser, "")
    editor.click()
    # Typed key by key, as a user types (the editor steps over the brackets it closed itself).
    for line in SMALL.format(colour="(0.9, 0.3, 0.2)").splitlines():
        editor.send_keys(line, Keys.ENTER)
    typed = browser.execute_script("return window.tracerPlayground.view.state.doc.toString()")
    state = wait_for_final_of_latest(browser)
    assert state["diagnostics"] == "", state
    assert canvas_rgb(browser) == native_rgb(tracer_bin, tmp_path, typed)


def test_a_mistake_shows_its_diagnostic_in_place_and_keeps_the_image(site_url, browser, tracer_bin, tmp_path):
    open_page(browser, site_url)
    good = SMALL.format(colour="(0.2, 0.4, 0.9)")
    set_text(browser, good)
    wait_for_final_of_latest(browser)
    before = canvas_rgb(browser)
    version = page_state(browser)["version"]
    broken = good.replace("radius 1.5", "radius 1.5 colour 3")
    set_text(browser, broken)
    WebDriverWait(browser, WAIT).until(lambda b: page_state(b)["diagnostics"])
    # The command line's own message, as it prints it (file:line:col, the source line, the caret).
    (tmp_path / "broken.scn").write_text(broken)
    cli = subprocess.run([tracer_bin, str(tmp_path / "broken.scn"), "--check"], capture_output=True, text=True)
    assert cli.returncode != 0
    shown = page_state(browser)["diagnostics"]
    assert shown == cli.stderr.replace(str(tmp_path / "broken.scn"), "/scenes/task2.scn")
    line, column = 3, broken.splitlines()[2].index("colour") + 1
    assert f"task2.scn:{line}:{column}: error:" in shown
    # In the editor: the error's range underlined on that line, at that column.
    marked = browser.execute_script(
        "const v = window.tracerPlayground.view; const r = document.querySelector('.cm-lintRange-error');"
        "if (!r) return null; const at = v.posAtDOM(r); const l = v.state.doc.lineAt(at);"
        "return [l.number, at - l.from + 1];"
    )
    assert marked == [line, column]
    assert page_state(browser)["version"] == version and canvas_rgb(browser) == before  # the last good image stays
    set_text(browser, good.replace("(0.2, 0.4, 0.9)", "(0.3, 0.8, 0.3)"))  # fixed: rendered again
    state = wait_for_final_of_latest(browser)
    assert state["diagnostics"] == "" and state["version"] > version
    assert browser.execute_script("return document.querySelectorAll('.cm-lintRange-error').length") == 0


@pytest.mark.parametrize("name", ["cubes.scn", "globe.scn"])
def test_a_gallery_scene_renders_as_the_command_line_renders_it(site_url, browser, tracer_bin, tmp_path, name):
    """cubes: an OBJ mesh from the bundle's file system; globe: a PNG picture the browser decoded."""
    open_page(browser, site_url)
    browser.execute_script(
        "const g = document.getElementById('gallery'); g.value = arguments[0]; g.dispatchEvent(new Event('change'));",
        f"/scenes/{name}",
    )
    WebDriverWait(browser, WAIT).until(lambda b: page_state(b)["jobs"] > 1)
    state = wait_for_final_of_latest(browser)
    assert state["diagnostics"] == "", state
    text = browser.execute_script("return window.tracerPlayground.view.state.doc.toString()")
    assert text == (ROOT / "scenes" / name).read_text()
    assert canvas_rgb(browser) == native_rgb(tracer_bin, tmp_path, scene_path=ROOT / "scenes" / name)


def test_a_share_link_carries_the_scene(site_url, browser):
    open_page(browser, site_url)
    text = SMALL.format(colour="(0.7, 0.7, 0.1)") + "# ünïcödé and a long line " + "x" * 300 + "\n"
    set_text(browser, text)
    browser.find_element(By.ID, "share").click()
    WebDriverWait(browser, WAIT).until(lambda b: "#in=" in b.current_url)
    link = browser.current_url
    browser.get("about:blank")
    browser.get(link)
    WebDriverWait(browser, WAIT).until(
        lambda b: b.execute_script(
            "return window.tracerPlayground && window.tracerPlayground.view.state.doc.toString()"
        )
        == text
    )
    assert wait_for_final_of_latest(browser)["diagnostics"] == ""


def test_an_edit_during_a_long_render_drops_it(site_url, browser):
    open_page(browser, site_url)
    long_render = SMALL.format(colour="0.5").replace("width 96 height 64", "width 1200 height 800 samples 16")
    set_text(browser, long_render)
    long_job = WebDriverWait(browser, WAIT).until(lambda b: page_state(b)["sent"] and page_state(b)["jobs"])
    # Under way: its preview drawn, the whole image not.
    WebDriverWait(browser, WAIT).until(
        lambda b: b.execute_script("return window.tracerPlayground.drawn.some(f => f.id === arguments[0])", long_job)
    )
    set_text(browser, SMALL.format(colour="0.8"))
    state = wait_for_final_of_latest(browser)
    assert state["job"] > long_job
    frames = browser.execute_script("return window.tracerPlayground.drawn")
    assert not any(f["id"] == long_job and f["final"] for f in frames), frames


def test_a_scene_that_runs_long_does_not_hold_up_the_next_edit(site_url, browser):
    """A load that runs for many seconds (a loop near the language's operation limit) is left
    behind: the worker is replaced and the next edit renders."""
    open_page(browser, site_url)
    slow = "let x = 0\nfor i in 0..899 { for j in 0..9999 { x = x + sqrt(j) * sqrt(i) + sqrt(j + 1) * sqrt(i + 2) } }\n"
    set_text(browser, slow + SMALL.format(colour="0.3"))  # 9 million iterations: seconds to run
    WebDriverWait(browser, WAIT).until(lambda b: page_state(b)["sent"])
    stuck = page_state(browser)["jobs"]
    set_text(browser, SMALL.format(colour="(0.1, 0.9, 0.9)"))
    state = wait_for_final_of_latest(browser)
    assert state["job"] > stuck and state["diagnostics"] == ""
    assert browser.execute_script("return window.tracerPlayground.restarts()") >= 1  # left behind, not waited for


def test_the_page_works_offline_once_loaded(own_server, browser):
    """After one visit the service worker holds every file: with the server gone, the page loads
    again and renders."""
    open_page(browser, own_server.url)
    cached = browser.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        "navigator.serviceWorker.ready.then(async () => {"
        "  for (let i = 0; i < 600; i++) {"
        "    const names = await caches.keys();"
        "    const keys = names.length ? await (await caches.open(names[0])).keys() : [];"
        "    if (keys.length >= 8) return done(keys.map((r) => r.url.split('/').pop()));"
        "    await new Promise((r) => setTimeout(r, 100));"
        "  }"
        "  done(null);"
        "});"
    )
    assert cached and {"tracer.wasm", "tracer.data", "app.js", "worker.js"} <= set(cached), cached
    own_server.stop()  # no network from here on: only the browser's cache
    browser.refresh()
    WebDriverWait(browser, WAIT).until(lambda b: b.execute_script("return !!window.tracerPlayground"))
    set_text(browser, SMALL.format(colour="(0.5, 0.2, 0.8)"))
    assert wait_for_final_of_latest(browser)["diagnostics"] == ""


def test_completion_and_hover_come_from_tracers_tables(site_url, browser, tracer_bin):
    """Typing in a block offers its keys; the top level offers the blocks; hovering a key shows its
    meaning: the same tables as `tracer --language-json` (the language server's)."""
    import json

    from selenium.webdriver.common.action_chains import ActionChains

    tables = json.loads(subprocess.run([tracer_bin, "--language-json"], capture_output=True, check=True).stdout)
    sphere = next(block for block in tables["blocks"] if block["kind"] == "sphere")
    open_page(browser, site_url)
    set_text(browser, SMALL.format(colour="0.5") + "\n")
    editor = browser.find_element(By.CSS_SELECTOR, ".cm-content")

    def offered():
        return browser.execute_script(
            "return [...document.querySelectorAll('.cm-tooltip-autocomplete li')].map(li => li.textContent)"
        )

    # At the top level, after "sph": the sphere block.
    browser.execute_script(
        "const v = window.tracerPlayground.view; v.focus(); v.dispatch({selection: {anchor: v.state.doc.length}});"
    )
    editor.send_keys("sph")
    WebDriverWait(browser, WAIT).until(lambda b: any(o.startswith("sphere") for o in offered()))
    # Inside a sphere block, after "ra": its key radius, and no top-level block.
    editor.send_keys(Keys.ESCAPE, Keys.BACKSPACE * 3, "sphere { ra")
    WebDriverWait(browser, WAIT).until(lambda b: any(o.startswith("radius") for o in offered()))
    assert not any(o.startswith("camera") for o in offered())
    editor.send_keys(Keys.ESCAPE)
    # Hover over the word radius on line 3: the key's meaning from the table.
    word = browser.execute_script(
        "const v = window.tracerPlayground.view; const line = v.state.doc.line(3);"
        "const at = line.from + line.text.indexOf('radius') + 2; const r = v.coordsAtPos(at);"
        "return [r.left, (r.top + r.bottom) / 2];"
    )
    body = browser.find_element(By.TAG_NAME, "body")
    ActionChains(browser).move_to_element_with_offset(body, 0, 0).perform()
    origin = browser.execute_script(
        "const r = document.body.getBoundingClientRect(); return [r.left + r.width / 2, r.top + r.height / 2];"
    )
    ActionChains(browser).move_to_element_with_offset(
        body, int(word[0] - origin[0]), int(word[1] - origin[1])
    ).perform()
    radius = next(key for key in sphere["keys"] if key["name"] == "radius")
    WebDriverWait(browser, WAIT).until(
        lambda b: radius["meaning"]
        in b.execute_script("const t = document.querySelector('.cm-tooltip-hover'); return t ? t.textContent : ''")
    )


@pytest.mark.parametrize("fragment", ["#z=", "#z=%%%", "#in=/etc/passwd&z=AAAA", "#z=" + "A" * 100000])
def test_a_broken_share_link_opens_the_default_scene(site_url, browser, fragment):
    """A fragment that is not a share link's (empty, not base64, not deflate, huge, a path outside
    the gallery) opens task2 and renders it, with no error."""
    browser.get(site_url + fragment)
    WebDriverWait(browser, WAIT).until(lambda b: b.execute_script("return !!window.tracerPlayground"))
    state = wait_for_final_of_latest(browser)
    assert state["diagnostics"] == ""
    text = browser.execute_script("return window.tracerPlayground.view.state.doc.toString()")
    assert text == (ROOT / "scenes" / "task2.scn").read_text()
