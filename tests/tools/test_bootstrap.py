"""tools/bootstrap --missing: the Debian packages it would install, from one dpkg-query of them all
(a stand-in dpkg-query on PATH here: one package unknown to dpkg, one known but not installed)."""

import os
import pathlib
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[2]

# Prints "ii  NAME" for every package asked about but these, as dpkg-query -W does, and exits with
# 1 as it does when a package is unknown to it.
FAKE_DPKG_QUERY = """#!/usr/bin/env bash
shift 2  # -W -f=FORMAT
status=0
for package in "$@"; do
  case "$package" in
    libglm-dev) echo "dpkg-query: no packages found matching $package" >&2; status=1 ;;
    povray) echo "un  povray" ;;
    *) echo "ii  $package" ;;
  esac
done
exit $status
"""


def missing(tmp_path: pathlib.Path, *options: str) -> subprocess.CompletedProcess:
    shims = tmp_path / "bin"
    shims.mkdir(exist_ok=True)
    fake = shims / "dpkg-query"
    fake.write_text(FAKE_DPKG_QUERY)
    fake.chmod(0o755)
    environment = dict(os.environ, PATH=f"{shims}:{os.environ['PATH']}")
    command = [str(ROOT / "tools" / "bootstrap"), "--missing", *options]
    return subprocess.run(command, capture_output=True, text=True, env=environment, timeout=60)


def test_the_packages_dpkg_does_not_have_installed_are_listed(tmp_path):
    result = missing(tmp_path, "--python")
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["libglm-dev", "povray"]  # unknown to dpkg; known, not installed


def test_without_python_its_packages_are_not_asked_for(tmp_path):
    result = missing(tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["libglm-dev"]


def test_nothing_missing_lists_nothing(tmp_path):
    result = subprocess.run([str(ROOT / "tools" / "bootstrap"), "--missing"], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout == ""  # this machine has what the build needs (the suite runs after it)
