"""
tracer's engine: use the tracer package (tracer.load, tracer.loads, Scene.render).
"""

from collections.abc import Sequence
from typing import Annotated

import numpy
from numpy.typing import NDArray


class Scene:
    """A scene loaded with its meshes and image files."""

def load(path: str, text: str | None, defines: Sequence[tuple[str, str]], include: Sequence[str]) -> tuple:
    """
    Loads a scene from path (or from text, named path); returns (Scene or None, report JSON).
    """

def describe(scene: Scene) -> str:
    """The resolved scene description as JSON text (tracer --dump-json)."""

def render(scene: Scene, overrides: Sequence[tuple[str, str]], threads: int, region: Sequence[int], stop: object | None, encoding: str | None) -> object:
    """
    Renders the scene; returns (float32 pixels of shape (height, width, 3), or uint8 ones with an encoding, statistics JSON), or None if stop() said so.
    """

def write_image(path: str, pixels: Annotated[NDArray[numpy.float32], dict(shape=(None, None, 3), order='C', device='cpu', writable=False)], encoding: str) -> None:
    """Writes pixels to path as the command line writes images (atomically)."""

def png_bytes(pixels: Annotated[NDArray[numpy.float32], dict(shape=(None, None, 3), order='C', device='cpu', writable=False)], encoding: str) -> bytes:
    """The pixels as an 8-bit PNG file's bytes."""

version: str = '0.1.0'
