"""ballista.models against the closed forms of the models (thesis seed 000 eq. 3.1-3.2) and the
command line's checks."""
import math

import pytest


def test_birkhoff_is_the_hydrodynamic_closed_form(ballista):
    # P = L sqrt(rho_p / rho_t), U = V / (1 + sqrt(rho_t / rho_p)) (thesis seed 000 eq. 3.1-3.2);
    # the same double-precision arithmetic, so to a few ulp.
    L, rho_p, rho_t, V = 0.07354, 19235.0, 2300.0, 3300.0
    r = ballista.models.evaluate("birkhoff", L=L, rho_p=rho_p, rho_t=rho_t, V=V)
    assert r["P"] == pytest.approx(L * math.sqrt(rho_p / rho_t), rel=1e-14)
    assert r["U"] == pytest.approx(V / (1 + math.sqrt(rho_t / rho_p)), rel=1e-14)
    assert r.units["P"] == "m" and r.units["U"] == "m/s"
    # By attribute, and the keyword `lambda` as lambda_.
    assert ballista.models.birkhoff(L=L, rho_p=rho_p, rho_t=rho_t)["P"] == r["P"]
    pj = ballista.models.particulated_jet(L=L, lambda_=1.0, rho_avg=rho_p, rho_t=rho_t)
    assert pj["P"] == pytest.approx(r["P"], rel=1e-14)  # lambda = 1: a continuous jet is Birkhoff's


def test_the_catalogue_lists_every_model_with_units(ballista):
    names = ballista.models.names()
    assert names[0] == "birkhoff" and "pack-evans" in names
    entry = ballista.models.describe("birkhoff")
    assert {p["key"]: p["unit"] for p in entry["params"]}["rho_t"] == "kg/m^3"
    with pytest.raises(KeyError, match="birkhoff"):
        ballista.models.describe("birkhof")


def test_bad_parameters_raise_naming_them(ballista):
    with pytest.raises(ballista.Error, match="rho_x"):
        ballista.models.evaluate("birkhoff", L=0.1, rho_p=19235, rho_t=2300, rho_x=1)
    with pytest.raises(ballista.Error, match="rho_t"):
        ballista.models.evaluate("birkhoff", L=0.1, rho_p=19235)
    with pytest.raises(ballista.Error, match="not a finite number"):
        ballista.models.evaluate("birkhoff", L=1e308, rho_p=1e308, rho_t=1e-308)
