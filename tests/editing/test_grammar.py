"""The highlighting grammar (grammar/vscode/syntaxes/tracer.tmLanguage.json): generated from
tracer's tables, and, tokenized by VS Code's own engine (vscode-textmate on Oniguruma, from
npm), it gives every shipped scene and every example in grammar/ a scope for each character
with no `invalid` token; text the language has no place for does get one."""

import json
import re
import shutil
import subprocess

import pytest
from conftest import ROOT, SCENES

from tracer_tools.editing import textmate

HERE = ROOT / "tests" / "editing" / "textmate"


@pytest.fixture(scope="module")
def tokenize():
    if not (shutil.which("node") and shutil.which("npm")):
        pytest.skip("Node.js and npm are not installed: the grammar's tokenizer test needs them")
    if not (HERE / "node_modules" / "vscode-textmate").is_dir():
        subprocess.run(["npm", "ci", "--no-audit", "--no-fund", "--silent"], cwd=HERE, check=True, timeout=600)

    def run(paths):
        result = subprocess.run(
            ["node", str(HERE / "tokenize.mjs"), str(textmate.GRAMMAR), *map(str, paths)],
            capture_output=True,
            text=True,
            check=True,
            timeout=300,
        )
        return {entry["file"]: entry["tokens"] for entry in json.loads(result.stdout)}

    return run


def test_the_committed_grammar_is_generated_from_the_tables(tracer_bin):
    tables = json.loads(
        subprocess.run([str(tracer_bin), "--language-json"], capture_output=True, text=True, check=True).stdout
    )
    assert textmate.GRAMMAR.read_text() == textmate.text(tables), "run tools/make-grammar"


def examples(tmp_path):
    """Every ```scn example of grammar/README.md and grammar/reference.md, each in a file."""
    paths = []
    for document in ("README.md", "reference.md"):
        text = (ROOT / "grammar" / document).read_text()
        for i, example in enumerate(re.findall(r"```scn\n(.*?)```", text, re.S)):
            path = tmp_path / f"{document}.{i}.scn"
            path.write_text(example)
            paths.append(path)
    return paths


def test_every_scene_and_example_is_highlighted_without_an_invalid_token(tokenize, tmp_path):
    paths = sorted(SCENES.rglob("*.scn")) + examples(tmp_path)
    assert len(paths) > 30
    tokens = tokenize(paths)
    assert len(tokens) == len(paths)
    for path, found in tokens.items():
        invalid = [t for t in found if any(s.startswith("invalid") for s in t[3])]
        assert not invalid, f"{path}: {invalid[:5]}"
        assert any("entity.name.type.block.tracer" in t[3] for t in found), path


def test_scopes_of_each_kind_of_word_and_the_invalid_ones(tokenize, tmp_path):
    path = tmp_path / "kinds.scn"
    path.write_text(
        "let r = sqrt(2) * pi  # a comment\nfor i in 0..3 { sphere { radius r } }\n"
        'include "lib.scn"\nrender { accel sah }\nsphere @ "unterminated\n'
    )
    tokens = tokenize([path])[str(path)]
    scope = {text: scopes[-1] for _, _, text, scopes in tokens if text.strip()}
    assert scope["let"] == scope["for"] == scope["include"] == "keyword.control.tracer"
    assert scope["sqrt"] == "support.function.builtin.tracer"
    assert scope["pi"] == "support.constant.builtin.tracer"
    assert scope["sphere"] == "entity.name.type.block.tracer"
    assert scope["radius"] == "variable.other.property.key.tracer"
    assert scope["sah"] == "constant.language.choice.tracer"
    assert scope["r"] == "variable.other.tracer"
    assert scope["0"] == scope["3"] == "constant.numeric.tracer"
    assert scope[".."] == "keyword.operator.tracer"
    assert scope["# a comment"] == "comment.line.number-sign.tracer"
    assert scope['"lib.scn"'] == "string.quoted.double.tracer"
    assert scope["@"] == "invalid.illegal.character.tracer"
    assert scope['"unterminated'] == "invalid.illegal.unterminated-string.tracer"
