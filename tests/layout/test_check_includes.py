"""tests/layout/check_includes.py on trees made here: an arrow up the stages, and a stage reaching
into another's internal/ folder, are each named; the stage's own internal/ is allowed."""

import pathlib
import subprocess
import sys

CHECK = pathlib.Path(__file__).resolve().parent / "check_includes.py"


def check(tmp_path, files: dict[str, str]) -> subprocess.CompletedProcess:
    for name, text in files.items():
        path = tmp_path / "src" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return subprocess.run([sys.executable, CHECK, tmp_path / "src"], capture_output=True, text=True)


def test_includes_down_the_stages_and_into_the_own_back_room_pass(tmp_path):
    result = check(
        tmp_path,
        {
            "app/main.cpp": '#include "lang/load_scene.h"\n#include "render/renderer.h"\n',
            "lang/parser.cpp": '#include "lang/internal/parser_class.h"\n#include "scene/scene.h"\n',
            "lang/internal/parser_class.h": '#include "lang/internal/syntax_tree.h"\n',
        },
    )
    assert result.returncode == 0, result.stdout
    assert "3 files checked, 0 problems" in result.stdout


def test_an_arrow_up_and_a_reach_into_another_back_room_are_named(tmp_path):
    result = check(
        tmp_path,
        {
            "accel/world.cpp": '#include "lang/schema.h"\n',
            "app/main.cpp": '#include "lang/internal/runtime_value.h"\n',
        },
    )
    assert result.returncode == 1
    assert "accel/world.cpp:1: accel/ includes lang/" in result.stdout
    assert "app/main.cpp:1: app/ includes lang/internal/" in result.stdout
