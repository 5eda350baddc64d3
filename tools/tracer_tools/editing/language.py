"""The scene language as tracer describes it (tracer --language-json): its block tables,
statements, expression words and built-ins, turned into an editor's hover text and completions."""

import json
import subprocess
from dataclasses import dataclass


@dataclass
class Entry:
    """One thing an editor can complete and explain."""

    label: str
    kind: str  # "block", "key", "statement", "word", "function", "constant"
    detail: str  # one line
    documentation: str  # Markdown


class Language:
    def __init__(self, tables: dict):
        self.blocks = {block["kind"]: block for block in tables["blocks"]}
        self.library: dict[str, str] = tables.get("library", {})  # the standard library's files: name -> text
        self.top_level = [block["kind"] for block in tables["blocks"] if block["top_level"]]
        self.patterns = [block["kind"] for block in tables["blocks"] if block.get("pattern")]
        self.words: dict[str, Entry] = {}
        for statement in tables["statements"]:
            if statement["keyword"]:
                previous = self.words.get(statement["keyword"])
                text = f"`{statement['syntax']}`: {statement['meaning']}"
                documentation = f"{previous.documentation}\n\n{text}" if previous else text
                self.words[statement["keyword"]] = Entry(
                    statement["keyword"], "statement", statement["syntax"], documentation
                )
        for word in tables["words"]:
            self.words.setdefault(word["word"], Entry(word["word"], "word", word["word"], word["meaning"]))
        for constant in tables["constants"]:
            self.words[constant["name"]] = Entry(
                constant["name"], "constant", constant["meaning"], f"`{constant['name']}`: {constant['meaning']}"
            )
        for function in tables["functions"]:
            arguments = ", ".join("abcdefgh"[: function["arity"]])
            signature = f"{function['name']}({arguments})"
            self.words[function["name"]] = Entry(
                function["name"], "function", signature, f"`{signature}`: {function['meaning']}"
            )

    @classmethod
    def from_tracer(cls, tracer: str) -> "Language":
        result = subprocess.run([tracer, "--language-json"], capture_output=True, text=True, check=True, timeout=30)
        return cls(json.loads(result.stdout))

    def block_entry(self, kind: str) -> Entry:
        block = self.blocks[kind]
        keys = "\n".join(f"- `{key['name']}`: {key['meaning']}" for key in block["keys"])
        written = f"`{kind}{' NAME' if block['named'] else ''} {{ ... }}`"
        return Entry(kind, "block", block["summary"], f"{written}: {block['summary']}\n\n{keys}")

    def key_entry(self, kind: str, name: str) -> Entry | None:
        for key in self.blocks.get(kind, {}).get("keys", []):
            if key["name"] == name:
                default = "required" if key["default"] is None else f"default `{key['default']}`"
                documentation = (
                    f"`{kind}.{name}`: {key['meaning']}\n\n{key['type']}; {default}; " f"allowed: {key['allowed']}"
                )
                return Entry(name, "key", f"{key['type']} ({default})", documentation)
        return None

    def keys(self, kind: str) -> list[Entry]:
        return [self.key_entry(kind, key["name"]) for key in self.blocks.get(kind, {}).get("keys", [])]

    def key_takes_pattern(self, kind: str, name: str) -> bool:
        """True if the key's value may be a pattern (ka, kd, a checker's squares)."""
        return any(
            key["name"] == name and "pattern" in key["type"] for key in self.blocks.get(kind, {}).get("keys", [])
        )

    def key_is_material(self, kind: str, name: str) -> bool:
        return any(
            key["name"] == name and "material" in key["type"] for key in self.blocks.get(kind, {}).get("keys", [])
        )
