"""Small edits of a scene file's text, for the tools that render a committed scene with one
setting changed (the SPD suite, the POV-Ray table)."""

import pathlib
import re


def with_render_key(scn_path: pathlib.Path, out_path: pathlib.Path, key: str) -> None:
    """The scene with `key` (e.g. `transparent_shadows true`) added to its render block."""
    text = scn_path.read_text()
    if not re.search(r"^render \{", text, flags=re.MULTILINE):
        raise ValueError(f"{scn_path}: no render block to add {key} to")
    out_path.write_text(re.sub(r"^render \{", "render { " + key + " ", text, count=1, flags=re.MULTILINE))
