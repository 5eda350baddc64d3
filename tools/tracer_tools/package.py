"""The tracer Python package built beside a tracer executable (a build's python/ folder, where
tools/test and tools/bootstrap --python put it): the tools render in process with it where that
saves a process and a file (the farm's workers, the cross-check, the benchmarks)."""

from __future__ import annotations

import os
import sys
import types


def folder_beside(tracer: str | os.PathLike) -> str:
    """Where the build of the executable `tracer` puts the tracer package: its python/ folder."""
    return os.path.join(os.path.dirname(os.path.abspath(tracer)), "python")


def imported_beside(tracer: str | os.PathLike) -> types.ModuleType | None:
    """The tracer package built beside the executable `tracer` (folder_beside), imported with that
    folder first on the module path; None if it is not built there (or another one was imported)."""
    folder = folder_beside(tracer)
    if not os.path.isfile(os.path.join(folder, "tracer", "__init__.py")):
        return None
    if folder not in sys.path:
        sys.path.insert(0, folder)
    try:
        import tracer as package
    except ImportError:
        return None
    extension = os.path.abspath(package._tracer.__file__)
    return package if os.path.dirname(os.path.dirname(extension)) == folder else None
