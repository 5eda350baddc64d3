"""docs/architecture.md, the map of the source, names every folder of src/ and of
tools/tracer_tools/ (as `src/NAME/` and `tools/tracer_tools/NAME/`), and names no folder that is
gone; every Markdown page of docs/ is reached from docs/index.md by its links."""

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
MAP = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")


def folders(parent: str) -> set[str]:
    return {
        f"{parent}/{path.name}/"
        for path in (ROOT / parent).iterdir()
        if path.is_dir() and path.name != "__pycache__" and not path.name.startswith(".")
    }


def named_in_map(parent: str) -> set[str]:
    return set(re.findall(re.escape(parent) + r"/[a-z_]+/", MAP))


def test_every_folder_of_src_is_on_the_map():
    assert folders("src") - named_in_map("src") == set()
    assert named_in_map("src") - folders("src") == set()


def test_every_folder_of_the_tools_package_is_on_the_map():
    assert folders("tools/tracer_tools") - named_in_map("tools/tracer_tools") == set()
    assert named_in_map("tools/tracer_tools") - folders("tools/tracer_tools") == set()


def linked_pages(page: pathlib.Path) -> set[pathlib.Path]:
    """The Markdown pages that `page` links to (relative links, anchors dropped)."""
    text = page.read_text(encoding="utf-8")
    return {(page.parent / target).resolve() for target in re.findall(r"\]\(([^)#:]+\.md)", text)}


def test_every_page_of_docs_is_reached_from_the_index():
    index = (ROOT / "docs" / "index.md").resolve()
    reached, waiting = {index}, [index]
    while waiting:
        for page in linked_pages(waiting.pop()):
            assert page.is_file(), f"a link to {page}, which does not exist"
            if page not in reached and ROOT / "docs" in page.parents:
                reached.add(page)
                waiting.append(page)
    pages = {path.resolve() for path in (ROOT / "docs").rglob("*.md")}
    assert pages - reached == set()
