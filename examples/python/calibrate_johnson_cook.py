#!/usr/bin/python3
"""Calibrates the Johnson-Cook strength constants A and B of OFHC copper against a tensile
stress-strain table: scipy's least squares drives one material point through ballista.drive
(uniaxial stress, in memory) at every trial (A, B). docs/python.md.

The table is the Johnson-Cook law of Johnson & Cook (1983) for OFHC copper, A = 90 MPa,
B = 292 MPa, n = 0.31 (the `copper_ofhc_jc` preset, data/materials.yaml), evaluated as true stress
against true strain at ten strains: a table whose answer is known, so the loop is checked when it
returns A and B (tests/python/test_examples.py). Put measured (true strain, true stress in Pa)
pairs in TABLE to calibrate against a test instead. The test is taken as quasi-static and
isothermal: rate term and adiabatic heating off (jc_c = 0, taylor_quinney = 0).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/calibrate_johnson_cook.py
"""
import time

import numpy as np
from scipy.optimize import least_squares

import ballista

A_TRUE, B_TRUE, N = 90e6, 292e6, 0.31
E = 9 * 129e9 * 46e9 / (3 * 129e9 + 46e9)  # Young's modulus of the preset's K and G


def johnson_cook_table(plastic_strains):
    """(true strain, true stress): sigma = A + B eps_p^n (Johnson & Cook 1983, eq. 1 at the
    reference rate and temperature), total strain eps_p + sigma / E."""
    sigma = A_TRUE + B_TRUE * plastic_strains**N
    return plastic_strains + sigma / E, sigma


TABLE = np.column_stack(johnson_cook_table(np.linspace(0.02, 0.5, 10)))

DECK = {
    "materials": {"cu": {"preset": "copper_ofhc_jc", "jc_c": 0.0, "taylor_quinney": 0.0,
                         "failure": {"criterion": "none"}}},
    # Tension to the table's last strain and a little past it, lateral stresses held at zero:
    # 1 s for a strain rate of ~0.5/s (quasi-static; the rate term is off anyway).
    "drive": {"legs": [{"duration": 1.0, "steps": 600, "strain": {"11": float(TABLE[-1, 0]) * 1.05},
                        "stress": {"22": 0, "33": 0}}]},
}


def stress_at_table_strains(a, b):
    """True stress of the driven point at the table's true strains, Pa."""
    h = ballista.drive(DECK, overrides={"materials.cu.jc_a": a, "materials.cu.jc_b": b})
    strain = np.log(h["F11"])  # uniaxial stretch along 1 with no rotation: true strain ln F11
    return np.interp(TABLE[:, 0], strain, h["sigma_11"])


def calibrate(start=(50e6, 500e6)):
    """(A, B) minimising the relative stress misfit over the table, and the number of drives."""
    calls = [0]

    def residual(x):
        calls[0] += 1
        return stress_at_table_strains(x[0] * 1e8, x[1] * 1e8) / TABLE[:, 1] - 1.0

    fit = least_squares(residual, np.array(start) / 1e8, bounds=([1e-3, 0.0], [10.0, 10.0]), x_scale="jac")
    return fit.x * 1e8, calls[0], float(np.abs(fit.fun).max())


if __name__ == "__main__":
    t0 = time.perf_counter()
    (a, b), calls, misfit = calibrate()
    wall = time.perf_counter() - t0
    print(f"A = {a / 1e6:.3f} MPa (table's {A_TRUE / 1e6:g}), B = {b / 1e6:.3f} MPa (table's {B_TRUE / 1e6:g}), "
          f"n = {N} held")
    print(f"largest stress misfit {misfit:.2e}; {calls} drives of 600 steps in {wall:.2f} s "
          f"({calls * 600 / wall:.3g} steps/s)")
