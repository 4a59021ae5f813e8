#!/usr/bin/python3
"""How the fragmentation scripts read a steel's strength (docs/validation.md, "What the steels' yield
stresses mean to the bonds"): validation/exploding_cylinders.py --strength flow gives each
configuration's yield as peridynamics.flow_stress and clears the example's yield_stress (the solver
refuses both: tests/unit/peridynamics/test_pd_solver.cpp), and keeps the first-yield overrides
untouched otherwise; and
validation/expanding_ring_theory.py takes the ring's flow stress as its bonds' 2D plateau, the
factor 1.4115486 of src/peridynamics/bond_constants.hpp (PdSolver.MicroPlasticPlateauUnderUniaxial...
holds the same constant to 1e-7), or the deck's flow_stress when it gives one."""
import os
import sys
import tempfile

import yaml

import script_args

a = script_args.parse()
import exploding_cylinders as ec  # noqa: E402
import expanding_ring_theory as ring  # noqa: E402

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


for name, overrides in ec.CONFIGS.items():
    first = ec.strength(name, "first_yield")
    check(first == overrides[0], f"{name}: first yield keeps the configuration's overrides")
    flow = ec.strength(name, "flow")
    given = [s for s in overrides[0] if s.startswith("peridynamics.yield_stress=")]
    expected = float(given[0].split("=")[1]) if given else ec.EXAMPLE_YIELD
    check("peridynamics.yield_stress=~" in flow, f"{name}: flow clears yield_stress")
    values = [float(s.split("=")[1]) for s in flow if s.startswith("peridynamics.flow_stress=")]
    check(values == [expected], f"{name}: flow_stress {values} = the configuration's yield {expected:g}")
    check(len([s for s in flow if s.startswith("peridynamics.yield_stress=") and s != "peridynamics.yield_stress=~"]) == 0,
          f"{name}: no yield_stress value left beside flow_stress")
example = yaml.safe_load(open(ec.DECK))
check(float(example["peridynamics"]["yield_stress"]) == ec.EXAMPLE_YIELD, "EXAMPLE_YIELD is the example's yield_stress")

check(abs(ring.flow_factor_2d() - 1.4115486278030973) < 1e-12, f"2D plateau factor {ring.flow_factor_2d():.12g}")
r = ring.ring_data(ring.DECK)
check(abs(r["flow_stress"] / r["yield_stress"] - ring.flow_factor_2d()) < 1e-12, "the ring flows at 1.4115 x its yield")
deck = yaml.safe_load(open(ring.DECK))
deck["peridynamics"].pop("yield_stress")
deck["peridynamics"]["flow_stress"] = 9.0e8
os.makedirs(a.out, exist_ok=True)
path = os.path.join(a.out, "ring_flow.yaml")
yaml.safe_dump(deck, open(path, "w"))
check(ring.ring_data(path)["flow_stress"] == 9.0e8, "a deck's flow_stress is the ring's flow stress")

sys.exit(1 if failures else 0)
