"""The Python guide's examples (docs/guide/python.md) run as written, in order, from the checkout's
root: every ```python block of the page, one namespace, as a reader pasting them into a notebook."""

import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "guide" / "python.md"


def test_the_guides_examples_run(tmp_path, monkeypatch):
    pytest.importorskip("mitsuba", reason="the guide compares with Mitsuba 3 (tools/bootstrap --python installs it)")
    blocks = re.findall(r"```python\n(.*?)```", GUIDE.read_text(), re.S)
    assert len(blocks) >= 5, "the guide's examples were not found"
    monkeypatch.chdir(ROOT)
    namespace = {}
    for number, block in enumerate(blocks, 1):
        # Files the examples write go to a temporary folder, not the checkout.
        code = re.sub(r'"(out[^"]*\.(png|exr))"', lambda m: repr(str(tmp_path / m.group(1))), block)
        exec(compile(code, f"{GUIDE.name}, example {number}", "exec"), namespace)
    assert (tmp_path / "out.exr").is_file() and namespace["np"].abs(
        namespace["ours"] - namespace["theirs"]
    ).mean() < 0.01
