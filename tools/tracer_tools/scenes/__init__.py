"""Generators of test scenes and meshes: `tools/make-scene NAME` runs one (see __main__.GENERATORS)."""
