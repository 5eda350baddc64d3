"""The preview page (tools/preview) in a real headless browser: Debian's chromium, driven by
Selenium through chromium-driver. The page shows the image, updates after a save, and shows
tracer's diagnostics (with the caret) after a broken save, above the last good image."""

import os
import pathlib
import shutil
import signal

import pytest
from conftest import start_preview

SCENE = """camera {{ eye (0, 0, 7) lookat (0, 0, 0) }}
render {{ width {width} height 40 }}
sphere {{ center (0, 0, 0) radius 1 material {{ kd (1, 0.5, 0.2) }} }}
light {{ position (2, 3, 4) color 1 }}
"""

CHROMIUM = shutil.which("chromium")
CHROMEDRIVER = shutil.which("chromedriver")
pytestmark = pytest.mark.skipif(
    not (CHROMIUM and CHROMEDRIVER),
    reason="Debian's chromium and chromium-driver are not installed (tools/bootstrap " "--python installs them)",
)


@pytest.fixture
def preview(tracer_bin, tmp_path):
    scene = tmp_path / "scene.scn"
    scene.write_text(SCENE.format(width=60))
    process = start_preview(tracer_bin, scene, tmp_path / "out.png", 0)
    line = process.stdout.readline()
    assert line.startswith("tools/preview: http://127.0.0.1:"), line
    yield scene, line.split()[1]
    process.send_signal(signal.SIGINT)
    assert process.wait(timeout=20) == 0


@pytest.fixture
def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"):
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    yield driver
    driver.quit()


def save(path, text):
    temporary = path.with_name(path.name + ".new")
    temporary.write_text(text)
    os.replace(temporary, path)


def test_the_page_shows_the_image_then_updates_then_shows_an_error(preview, browser, tmp_path):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    scene, url = preview
    browser.get(url)
    wait = WebDriverWait(browser, 30)
    image = browser.find_element(By.ID, "image")
    summary = browser.find_element(By.ID, "summary")
    diagnostics = browser.find_element(By.ID, "diagnostics")

    def loaded_image():  # the browser decoded it: its natural size is the image's
        return browser.execute_script(
            "const i = arguments[0]; return i.complete ? [i.naturalWidth, " "i.naturalHeight] : null", image
        )

    wait.until(lambda _: loaded_image() == [60, 40])
    assert "60x40" in summary.text
    assert diagnostics.text == ""
    first_version = int(image.get_attribute("data-version"))

    save(scene, SCENE.format(width=80))  # a save: the page follows by itself
    wait.until(lambda _: loaded_image() == [80, 40])
    assert "80x40" in summary.text
    assert int(image.get_attribute("data-version")) > first_version
    version = image.get_attribute("data-version")

    save(scene, SCENE.format(width=80).replace("radius 1", "radius 1 fuzz 2"))  # a broken save
    wait.until(lambda _: "error" in diagnostics.text)
    lines = diagnostics.text.splitlines()
    assert lines[0] == f"{scene}:3:36: error: unknown key 'fuzz' in sphere", lines
    assert lines[1].startswith("sphere { center (0, 0, 0) radius 1 fuzz 2")
    assert lines[2] == " " * 35 + "^~~~", "the caret under the key, as in the terminal"
    assert "last good image" in summary.text
    assert image.get_attribute("data-version") == version and loaded_image() == [80, 40]
    browser.save_screenshot(str(tmp_path / "page.png"))
    assert pathlib.Path(tmp_path / "page.png").stat().st_size > 0
