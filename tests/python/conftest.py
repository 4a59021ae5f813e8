"""Shared by the Python module's tests: where the sources and the command line are (set by
tests/python/CMakeLists.txt), and a helper that runs `ballista` for a comparison."""
import os
import subprocess

import pytest

SOURCE = os.environ.get("BALLISTA_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))
EXE = os.environ.get("BALLISTA_EXE", os.path.join(SOURCE, "build", "ballista"))


def example(name):
    return os.path.join(SOURCE, "examples", name)


def cli(*args):
    """Runs the command line; returns its completed process (a failure fails the test)."""
    proc = subprocess.run([EXE, *args], capture_output=True, text=True)
    assert proc.returncode == 0, f"{' '.join(args)}: exit {proc.returncode}\n{proc.stderr}"
    return proc


@pytest.fixture
def ballista():
    import ballista as module
    return module
