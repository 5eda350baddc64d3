"""Shared set-up of the benchmark scripts' tests: the tools on sys.path."""

import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
