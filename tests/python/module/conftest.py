"""Fixtures of the Python module's tests: the CLI to compare with, the source tree, a scratch
directory as the current one (so that anything written by mistake would be seen)."""

import os
import subprocess

import pytest

SOURCE = os.environ.get("ROTGEN_SOURCE_DIR",
                        os.path.abspath(os.path.join(os.path.dirname(__file__), "../../..")))
ROTGEN = os.environ.get("ROTGEN_EXE", os.path.join(SOURCE, "build", "rotgen"))


def source(*parts):
    return os.path.join(SOURCE, *parts)


def run_cli(*args, cwd=None):
    """`rotgen ARGS`: (exit status, stdout, stderr)."""
    p = subprocess.run([ROTGEN, *args], capture_output=True, text=True, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


@pytest.fixture
def in_tmp(tmp_path, monkeypatch):
    """The test runs in an empty directory of its own."""
    monkeypatch.chdir(tmp_path)
    return tmp_path
