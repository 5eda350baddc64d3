"""Writes scenes/meshes/bunny.obj from the npm package `bunny` 1.0.1 (the Stanford bunny,
public domain; 1,839 vertices, 3,674 triangles).

    tools/make-scene bunny-obj                 # runs `npm pack bunny@1.0.1` in a temporary folder
    tools/make-scene bunny-obj --tgz FILE      # or reads a tarball you already have

The package's index.js holds `exports.positions=[[x,y,z],...]` and `exports.cells=[[a,b,c],...]`
(0-based). Each number is copied as text, exactly as the package writes it; cells become
1-based `f` lines. Nothing is rescaled: scenes place the mesh with their own transform.
"""

import argparse
import pathlib
import re
import subprocess
import sys
import tarfile
import tempfile

from tracer_tools import ROOT, option_types

PACKAGE = "bunny@1.0.1"
NUMBER = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"


def triples(array_text: str) -> list:
    return re.findall(rf"\[({NUMBER}),({NUMBER}),({NUMBER})\]", array_text)


def convert(index_js: str) -> str:
    positions_text = re.search(r"exports\.positions\s*=\s*(\[.*?\]\])", index_js, re.S).group(1)
    cells_text = re.search(r"exports\.cells\s*=\s*(\[.*?\]\])", index_js, re.S).group(1)
    positions, cells = triples(positions_text), triples(cells_text)
    if len(positions) != 1839 or len(cells) != 3674:
        sys.exit(f"unexpected package contents: {len(positions)} vertices, {len(cells)} triangles")
    lines = [
        "# The Stanford bunny (Stanford Computer Graphics Laboratory), from the npm package",
        '# bunny 1.0.1 by Mikola Lysenko, licence "Public Domain". Written by',
        "# tools/make-scene bunny-obj: numbers exactly as index.js has them, cells made 1-based.",
        f"# {len(positions)} vertices, {len(cells)} triangles, closed, no normals.",
    ]
    lines += [f"v {x} {y} {z}" for x, y, z in positions]
    lines += [f"f {int(a) + 1} {int(b) + 1} {int(c) + 1}" for a, b, c in cells]
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--tgz", type=option_types.existing_file, help="an already downloaded bunny-1.0.1.tgz")
    parser.add_argument(
        "-o", "--output", type=option_types.output_file, default=ROOT / "scenes" / "meshes" / "bunny.obj"
    )
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tgz = args.tgz
        if tgz is None:
            subprocess.run(["npm", "pack", PACKAGE, "--silent"], cwd=tmp, check=True, stdout=subprocess.DEVNULL)
            tgz = pathlib.Path(tmp) / "bunny-1.0.1.tgz"
        with tarfile.open(tgz) as archive:
            index_js = archive.extractfile("package/index.js").read().decode()
    args.output.write_text(convert(index_js))
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
