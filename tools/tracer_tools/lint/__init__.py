"""Checks of tools/lint beyond formatting: the length of functions."""
