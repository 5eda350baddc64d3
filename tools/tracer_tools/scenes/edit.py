"""Small edits of a scene file's text, for the tools that render a committed scene with one
setting changed (the SPD suite, the POV-Ray table)."""

import pathlib
import re


def with_render_key(scn_path: pathlib.Path, out_path: pathlib.Path, key: str) -> None:
    """The scene with `key` (e.g. `transparent_shadows true`) in its render block: its value
    replaced where the block sets the key already (the block's first line to the first `}`),
    else added."""
    text = scn_path.read_text()
    block = re.search(r"^render \{[^}]*", text, flags=re.MULTILINE)
    if not block:
        raise ValueError(f"{scn_path}: no render block to add {key} to")
    name = key.split()[0]
    body, count = re.subn(rf"\b{re.escape(name)}\s+\S+", key, block[0], count=1)
    if not count:
        body = block[0].replace("render {", "render { " + key + " ", 1)
    out_path.write_text(text[: block.start()] + body + text[block.end() :])
