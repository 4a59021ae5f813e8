"""The Python examples (examples/python/) run and reach their answers."""
import importlib.util

import pytest

from conftest import SOURCE


def load(name):
    spec = importlib.util.spec_from_file_location(name, f"{SOURCE}/examples/python/{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_johnson_cook_calibration_returns_the_tables_constants():
    jc = load("calibrate_johnson_cook")
    (a, b), calls, misfit = jc.calibrate()
    # The table is the Johnson-Cook law itself, so the fit must return its A and B. What is left
    # is the driven curve read between its 600 steps (linear interpolation of a curve whose slope
    # changes fastest near yield) and the elastic strain counted as sigma/E: measured 0.04 % on A
    # and 0.05 % on B; 0.3 % leaves room for another compiler's round-off, not for a wrong loop.
    assert a == pytest.approx(jc.A_TRUE, rel=3e-3)
    assert b == pytest.approx(jc.B_TRUE, rel=3e-3)
    assert misfit < 1e-3 and calls < 200
