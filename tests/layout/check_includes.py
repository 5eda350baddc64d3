#!/usr/bin/env python3
"""The source layout's one rule: a stage includes only the stages below it.

    base  <  scene  <  lang, io, accel  <  render  <  app  <  python, web

lang, io and accel are siblings and include none of each other; render sits on accel (the
renderer and its acceleration structures know nothing of the language or of files). A stage's
internal/ folder (src/lang/internal/) is its back room: only that stage includes it.
Fails, naming each offending line, otherwise.
Usage: check_includes.py SRC_DIR"""

import pathlib
import re
import sys

ALLOWED = {
    "base": {"base"},
    "scene": {"base", "scene"},
    "lang": {"base", "scene", "lang"},
    "io": {"base", "scene", "io"},
    "accel": {"base", "scene", "accel"},
    "render": {"base", "scene", "accel", "render"},
    "app": {"base", "scene", "lang", "io", "accel", "render", "app"},
    "python": {"base", "scene", "lang", "io", "accel", "render", "app", "python"},
    "web": {"base", "scene", "lang", "io", "accel", "render", "app", "web"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/([a-z_]+/)?')


def main() -> int:
    src = pathlib.Path(sys.argv[1])
    problems, checked = [], 0
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".h", ".cpp", ".inl"):
            continue
        stage = path.relative_to(src).parts[0]
        if stage not in ALLOWED:
            problems.append(f"{path}: not in a known stage folder ({', '.join(ALLOWED)})")
            continue
        checked += 1
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = INCLUDE.match(line)
            if match and match.group(1) not in ALLOWED[stage]:
                problems.append(f"{path}:{number}: {stage}/ includes {match.group(1)}/: {line.strip()}")
            elif match and match.group(2) == "internal/" and match.group(1) != stage:
                problems.append(f"{path}:{number}: {stage}/ includes {match.group(1)}/internal/: {line.strip()}")
    for problem in problems:
        print(problem)
    print(f"{checked} files checked, {len(problems)} problems")
    return 1 if problems or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
