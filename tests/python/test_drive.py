"""ballista.drive: a single material point from Python, against the closed form of J2 uniaxial
stress and against `ballista drive`'s history.csv for the same deck."""
import csv

import numpy as np
import pytest

from conftest import cli, example

E, NU, SIGMA_Y, H = 200e9, 0.3, 400e6, 2e9


def j2_deck(strain=-0.02, steps=400, yield_stress=SIGMA_Y):
    return {
        "materials": {"steel": {"model": "j2_plasticity", "density": 7850, "youngs_modulus": E,
                                "poisson_ratio": NU, "yield_stress": yield_stress, "hardening_modulus": H}},
        "drive": {"legs": [{"duration": 1e-3, "steps": steps, "strain": {"11": strain},
                            "stress": {"22": 0, "33": 0}}]},
    }


def test_uniaxial_stress_follows_linear_hardening(ballista):
    # J2 with linear isotropic hardening in uniaxial stress (Simo & Hughes 1998 §3.3): elastic
    # sigma = E eps up to the yield stress, then |sigma| = sigma_y + H eqps. The lateral stresses
    # are held to the drive's tolerance (1e-10 of the stress); the hardening law is integrated by
    # radial return, exact for linear hardening, so both hold to round-off (1e-9 relative).
    h = ballista.drive(j2_deck())
    sigma, eqps = -h["sigma_11"], h["eqps"]
    plastic = eqps > 0
    assert plastic.sum() > 300 and (~plastic).sum() > 5
    assert np.allclose(sigma[plastic], SIGMA_Y + H * eqps[plastic], rtol=1e-9)
    # First step, elastic: E times the step's logarithmic strain (0.02 / 400) to second order in it.
    assert sigma[1] == pytest.approx(E * 0.02 / 400, rel=1e-4)
    assert np.abs(h["sigma_22"]).max() <= 1e-9 * np.abs(sigma).max()
    assert h.stress().shape == (len(h), 3, 3)


def test_same_history_as_the_command_line(ballista, tmp_path):
    deck = example("drive_uniaxial_stress_j2.yaml")
    cli("drive", deck, "-o", str(tmp_path / "cli"), "-q")
    with open(tmp_path / "cli" / "history.csv", newline="") as f:
        rows = list(csv.reader(f))
    h = ballista.drive(deck)
    assert h.columns == rows[0]
    # history.csv holds shortest round-trip numbers: the same doubles, exactly.
    assert np.array_equal(h.values, np.array(rows[1:], dtype=float))


def test_overrides_and_errors(ballista):
    softer = ballista.drive(j2_deck(), overrides={"materials.steel.yield_stress": 2e8})
    assert -softer["sigma_11"][-1] == pytest.approx(2e8 + H * softer["eqps"][-1], rel=1e-9)
    bad = j2_deck()
    bad["drive"]["legs"][0]["stesss"] = {"22": 0}
    with pytest.raises(ballista.DeckError) as e:
        ballista.drive(bad)
    assert "unknown key 'stesss'" in str(e.value) and "did you mean" in str(e.value)
    assert e.value.key_path.endswith("stesss") and e.value.line > 0
    with pytest.raises(ballista.Error):
        ballista.drive({"materials": bad["materials"], "drive": {"table": [[0] + [1, 0, 0, 0, 1, 0, 0, 0, 1],
                                                                           [1] + [-1, 0, 0, 0, 1, 0, 0, 0, 1]]}})


def test_a_point_that_cannot_go_on_raises_with_its_history(ballista):
    # Perfect plasticity cannot carry a uniaxial stress above its yield stress: stress control has
    # no solution, and the drive stops naming the step; the history up to it comes with the error.
    deck = {"materials": {"s": {"model": "j2_plasticity", "density": 7850, "youngs_modulus": E,
                                "poisson_ratio": NU, "yield_stress": SIGMA_Y}},
            "drive": {"max_iterations": 20,
                      "legs": [{"duration": 1.0, "steps": 20, "stress": {"11": 2 * SIGMA_Y, "22": 0, "33": 0}}]}}
    with pytest.raises(ballista.PhysicsError) as e:
        ballista.drive(deck)
    h = e.value.history
    assert 2 <= len(h) < 21
    # The last row is the step that raised (iterations -1); every step before it is on or below
    # the yield surface (the radial return's round-off: 1e-9 relative).
    assert h["iterations"][-1] == -1 and np.all(h["iterations"][:-1] >= 0)
    assert np.all(h["sigma_11"][:-1] <= SIGMA_Y * (1 + 1e-9))
    assert "step" in str(e.value)
