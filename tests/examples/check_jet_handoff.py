#!/usr/bin/python3
"""The charge-to-target hand-on: a shaped charge's formed jet, written as a `jet:` table by
tools/jet_table.py, read by the perforation deck (ctest example.jet_handoff).

1. Runs examples/shaped_charge_jet_formation.yaml at 0.5 mm cells to 20 us, or reads such a run
   (--formation: in ctest, the run of verification.shaped_charge_theory, a fixture).
2. Writes its jet as a table of 8 pieces and checks the table against the particles directly: the
   pieces' masses pi r^2 L rho sum to the jet's mass, and their momenta M v to its axial momentum
   (both to 1e-9: the table is built to keep them), the velocities fall from the tip, the lengths
   tile the jet.
3. Runs examples/jet_casing_sandstone_mpm.yaml with `jet: {file: ...}` in place of its own
   segments (2 mm cells, to 30 us of main stage, when the first pieces have reached the casing; the
   box taller, to hold the long tip piece when it is inserted) and checks that every inserted piece
   was seeded with its table mass within 25 % (a 2 mm lattice seeding cylinders of 0.6 to 2 mm
   radius: one or two points across).

Usage: check_jet_handoff.py --ballista BIN --out DIR [--formation RUN]
"""
import argparse
import math
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
import yaml

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "tools"))
from jet_table import jet_table  # noqa: E402


def fail(msg):
    sys.stderr.write("check_jet_handoff: FAIL: " + msg + "\n")
    sys.exit(1)


def run(cmd):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        fail(" ".join(cmd) + " exited " + str(p.returncode) + ":\n" + p.stdout[-3000:])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ballista", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--formation", help="an existing run of the formation example (default: run it)")
    a = ap.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    form = a.formation
    if not form:
        form = os.path.join(a.out, "formation")
        run([a.ballista, "run", os.path.join(REPO, "examples", "shaped_charge_jet_formation.yaml"), "-o", form, "-q",
             "--no-plots", "--set", "grid.cell_size=0.5e-3"])
    rows, rep = jet_table(form, segments=8)
    rho = rep["density"]
    mass = sum(math.pi * r * r * L * rho for r, L, v, t in rows)
    momentum = sum(math.pi * r * r * L * rho * v for r, L, v, t in rows)
    if abs(mass / rep["mass"] - 1) > 1e-9:
        fail(f"the pieces' mass {mass} != the jet's {rep['mass']}")
    if abs(momentum / rep["momentum"] - 1) > 1e-9:
        fail(f"the pieces' momentum {momentum} != the jet's {rep['momentum']}")
    v = [r[2] for r in rows]
    if any(v[k + 1] >= v[k] for k in range(len(v) - 1)):
        fail(f"the pieces' velocities do not fall from the tip: {v}")
    with h5py.File(rep["file"]) as f:
        sel = (f["body"][:] == 1) & (f["v"][:, 1] > 2000.0)
        extent = f["x"][:, 1][sel].max() - f["x"][:, 1][sel].min()
    if abs(sum(r[1] for r in rows) / extent - 1) > 1e-9:
        fail("the pieces' lengths do not tile the jet")
    table = os.path.join(a.out, "jet.csv")
    with open(table, "w") as f:
        f.write("radius,length,velocity,insert_time\n")
        for r in rows:
            f.write(",".join(repr(x) for x in r) + "\n")
    deck = yaml.safe_load(open(os.path.join(REPO, "examples", "jet_casing_sandstone_mpm.yaml")))
    jet = next(b for b in deck["bodies"] if "jet" in b)
    del jet["jet"]["segments"]
    jet["jet"]["file"] = table
    # Another jet: the demo's grid study is not of this deck (and its record lies beside the demo).
    del deck["penetration"]["convergence_record"]
    # The demo's patches and step per region are for its own jet at its shipped cells (and the
    # patches' faces are no nodes of the 2 mm cells below).
    deck["grid"].pop("patches", None)
    deck["mpm"].pop("multirate", None)
    deck_file = os.path.join(a.out, "perforation.yaml")
    yaml.safe_dump(deck, open(deck_file, "w"), sort_keys=False)
    perf = os.path.join(a.out, "perforation")
    # The box reaches 60 mm behind the casing: the tip piece of a jet formed at 0.5 mm is ~20 mm long
    # and is inserted whole, its leading face 5 mm in front of the casing.
    run([a.ballista, "run", deck_file, "-o", perf, "-q", "--no-plots", "--set", "grid.cell_size=2.0e-3",
         "--set", "grid.refine=[]", "--set", "simulation.end_time=30.0e-6", "--set", "grid.upper=[0.04, 0.19]"])
    # Each piece inserted by the end (its free flight from the charge plane reached the insertion
    # plane) is seeded with the table's mass, to the 2 mm lattice's error.
    names = [b["name"] for b in deck["bodies"]]
    last = sorted(n for n in os.listdir(perf) if n.startswith("particles_") and n.endswith(".h5"))[-1]
    with h5py.File(os.path.join(perf, last)) as f:
        mine = f["body"][:] == names.index(jet["name"])
        seg, mass_p = f["segment"][:][mine], f["mass"][:][mine]
    inserted = sorted(set(int(k) for k in seg))
    if not inserted:
        fail("no piece of the jet was inserted by the end of the perforation run")
    ratios = []
    for k in inserted:
        r, L = rows[k][0], rows[k][1]
        want = math.pi * r * r * L * rho
        got = 2 * math.pi * float(np.sum(mass_p[seg == k]))
        ratios.append(round(got / want, 3))
        if abs(got / want - 1) > 0.25:
            fail(f"piece {k}: the perforation run seeded {got * 1e3:.4g} g for the table's {want * 1e3:.4g} g")
    print(f"check_jet_handoff: OK: {len(rows)} pieces, {rep['mass'] * 1e3:.4g} g, tip {v[0]:.0f} m/s; pieces "
          f"{inserted} inserted in the perforation run with {ratios} of the table's masses")


if __name__ == "__main__":
    main()
