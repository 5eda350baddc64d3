"""tracer_tools.scenes.edit: a render key set in a copy of a scene, whether or not its render
block sets it already (a scene with `transparent_shadows true` got it twice, an error)."""

import pytest

from tracer_tools.scenes import edit


def test_a_render_key_is_added_or_its_value_replaced(tmp_path):
    scene, copy = tmp_path / "in.scn", tmp_path / "out.scn"
    scene.write_text("render {\n  width 64\n  transparent_shadows true\n}\ncamera { }\n")
    edit.with_render_key(scene, copy, "transparent_shadows false")
    assert copy.read_text() == "render {\n  width 64\n  transparent_shadows false\n}\ncamera { }\n"
    edit.with_render_key(scene, copy, "spawn_rules spd")
    assert copy.read_text().startswith("render { spawn_rules spd \n  width 64\n  transparent_shadows true")
    scene.write_text("camera { }\n")
    with pytest.raises(ValueError, match="no render block"):
        edit.with_render_key(scene, copy, "spawn_rules spd")
