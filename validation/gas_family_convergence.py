#!/usr/bin/python3
"""The peridynamic gas under refinement, with its family kept from the reference configuration or
renewed in the current one, beside the same problem in MPM (continuum products): the tables of
docs/validation.md, "The peridynamic gas".

Two problems, TNT (preset tnt) against a strengthless steel case (yield 1 MPa), plane strain for
peridynamics:
  cylinder  the Gurney cylinder of tests/verification/test_pd_gas.cpp (charge radius 10 mm, case of
            M/C 1 and 2), lit on its axis, to 20 us; MPM's is the axisymmetric slab of
            tests/verification/gurney_cylinder_support.hpp. Read: the case's mass-weighted radial
            velocity.
  sandwich  a detonation sliding along the charge: a slab 6 mm thick and 40 mm long between two
            1.5 mm plates (M/C 2.41 per plate), lit at one end on its mid-plane, to 12 us; MPM plane
            strain. Read: the plates' mass-weighted normal velocity over the middle third of the
            length.
Each peridynamic run with gas_refamily_steps 0 (the reference family) and 5 (renewed), at
--cells; the kinetic energy over the chemical energy at the end beside it. A finished run
(its summary.json present) is not run again.

Usage: validation/gas_family_convergence.py --ballista build/ballista --out DIR [--cells 1e-3 5e-4 2.5e-4 1.25e-4]
About 3 minutes on 2 cores with the defaults.
"""
import argparse
import glob
import json
import math
import os
import subprocess

import h5py
import numpy as np

RHO_C, RHO_M = 1630.0, 7850.0  # kg/m^3: TNT and the case steel
A = 10.0e-3                    # m, the cylinder's charge radius
L, HALF, PLATE = 40e-3, 3e-3, 1.5e-3  # m, the sandwich's length, half thickness and plate

STEEL_PD = "steel: {model: linear_elastic, density: 7850, bulk_modulus: 160.0e9, shear_modulus: 79.0e9}"
STEEL_MPM = ("steel: {model: j2_plasticity, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.29, "
             "yield_stress: 1.0e6, hardening_modulus: 0.0}")
MPM = "mpm: {shape_function: gimp, update: musl, flip: 0.99}\n"


def cylinder(solver, mc, h):
    b = A * math.sqrt(1.0 + mc * RHO_C / RHO_M)
    if solver == "mpm":
        return f"""simulation: {{solver: mpm, dimension: axisymmetric, end_time: 20e-6, cfl: 0.3, on_particle_exit: delete}}
materials:
  tnt: {{preset: tnt}}
  {STEEL_MPM}
{MPM}grid: {{lower: [0, 0], upper: [0.08, 1.0e-3], cell_size: {h:g}, boundary: {{x_min: symmetry, y_min: symmetry, y_max: symmetry}}}}
bodies:
  - {{name: charge, material: tnt, shape: {{type: box, lower: [0, 0], upper: [{A}, 1.0e-3]}}, particles_per_cell: 2}}
  - {{name: case, material: steel, shape: {{type: box, lower: [{A}, 0], upper: [{b:.9g}, 1.0e-3]}}, particles_per_cell: 2}}
detonation: {{points: [{{position: [0, 0.5e-3], time: 0}}]}}
output: {{fields: [v, body, mass], interval: 5e-6}}
"""
    return f"""simulation: {{solver: peridynamics, dimension: plane_strain, end_time: 20e-6}}
peridynamics: {{m: 3, yield_stress: 1.0e6}}
materials:
  tnt: {{preset: tnt}}
  {STEEL_PD}
grid: {{lower: [-0.08, -0.08], upper: [0.08, 0.08], cell_size: {h:g}}}
bodies:
  - {{name: charge, material: tnt, shape: {{type: cylinder, center: [0, 0, 0], axis: z, radius: {A}}}}}
  - {{name: case, material: steel, shape: {{type: tube, center: [0, 0, 0], axis: z, radius: {b:.9g}, inner_radius: {A}}}}}
detonation: {{points: [{{position: [0, 0], time: 0}}]}}
output: {{fields: [v, body, mass], interval: 5e-6}}
"""


def sandwich(solver, h):
    ppc = ", particles_per_cell: 2" if solver == "mpm" else ""
    head = (f"simulation: {{solver: mpm, dimension: plane_strain, end_time: 12e-6, cfl: 0.3, on_particle_exit: delete}}\n"
            f"materials:\n  tnt: {{preset: tnt}}\n  {STEEL_MPM}\n{MPM}") if solver == "mpm" else (
            f"simulation: {{solver: peridynamics, dimension: plane_strain, end_time: 12e-6}}\n"
            f"peridynamics: {{m: 3, yield_stress: 1.0e6}}\nmaterials:\n  tnt: {{preset: tnt}}\n  {STEEL_PD}\n")
    return head + f"""grid: {{lower: [-0.05, -0.05], upper: [0.09, 0.05], cell_size: {h:g}}}
bodies:
  - {{name: charge, material: tnt, shape: {{type: box, lower: [0, {-HALF}], upper: [{L}, {HALF}]}}{ppc}}}
  - {{name: top, material: steel, shape: {{type: box, lower: [0, {HALF}], upper: [{L}, {HALF + PLATE}]}}{ppc}}}
  - {{name: bottom, material: steel, shape: {{type: box, lower: [0, {-HALF - PLATE}], upper: [{L}, {-HALF}]}}{ppc}}}
detonation: {{points: [{{position: [0, 0], time: 0}}]}}
output: {{fields: [v, body, mass], interval: 12e-6}}
"""


def run(args, name, deck, renew=None):
    out = os.path.join(args.out, name)
    if not os.path.exists(os.path.join(out, "summary.json")):
        os.makedirs(args.out, exist_ok=True)
        path = os.path.join(args.out, name + ".yaml")
        with open(path, "w") as f:
            f.write(deck)
        cmd = [args.ballista, "run", path, "-o", out, "-q", "--no-plots", "--overwrite", "--threads", str(args.threads)]
        if renew is not None:
            cmd += ["--set", f"peridynamics.gas_refamily_steps={renew}"]
        subprocess.run(cmd, check=True)
    return out


def read(out, problem, axisymmetric):
    """(velocity m/s, kinetic over chemical energy, residual over chemical energy) at the last file."""
    with h5py.File(sorted(glob.glob(os.path.join(out, "particles_*.h5")))[-1]) as f:
        x, v, body, m = f["x"][:], f["v"][:], f["body"][:], f["mass"][:]
    if problem == "cylinder":
        s = body == 1
        vr = v[s, 0] if axisymmetric else (x[s, 0] * v[s, 0] + x[s, 1] * v[s, 1]) / np.hypot(x[s, 0], x[s, 1])
        vel = float(np.sum(m[s] * vr) / np.sum(m[s]))
    else:
        mid = (x[:, 0] >= L / 3) & (x[:, 0] < 2 * L / 3)
        top, bottom = mid & (body == 1), mid & (body == 2)
        vel = 0.5 * float(np.sum(m[top] * v[top, 1]) / np.sum(m[top]) - np.sum(m[bottom] * v[bottom, 1]) / np.sum(m[bottom]))
    e = json.load(open(os.path.join(out, "summary.json")))["energy"]
    return vel, e["kinetic"] / e["chemical_energy"], e["residual"] / e["chemical_energy"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ballista", default="build/ballista")
    ap.add_argument("--out", required=True)
    ap.add_argument("--cells", type=float, nargs="+", default=[1e-3, 5e-4, 2.5e-4, 1.25e-4])
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    cases = [("cylinder M/C 1", "cylinder", lambda s, h: cylinder(s, 1.0, h)),
             ("cylinder M/C 2", "cylinder", lambda s, h: cylinder(s, 2.0, h)),
             ("sandwich", "sandwich", sandwich)]
    cells = sorted(args.cells, reverse=True)
    print("| problem | " + " | ".join(f"{h * 1e3:g} mm" for h in cells) + " |")
    print("|---|" + "---|" * len(cells))
    for label, problem, deck in cases:
        tag = label.replace(" ", "_").replace("/", "")
        ref = {h: read(run(args, f"{tag}_mpm_h{h * 1e3:g}", deck("mpm", h)), problem, problem == "cylinder")
               for h in cells}
        finest = ref[cells[-1]][0]
        print(f"| {label}, MPM | " + " | ".join(f"{ref[h][0]:.0f} (KE {ref[h][1]:.2f})" for h in cells) + " |")
        for renew, family in ((0, "reference family"), (5, "renewed family")):
            row = []
            for h in cells:
                vel, ke, res = read(run(args, f"{tag}_pd{renew}_h{h * 1e3:g}", deck("pd", h), renew), problem, False)
                row.append(f"{vel:.0f} ({100 * (vel / finest - 1):+.1f} %, KE {ke:.2f}, residual {100 * res:.1f} %)")
            print(f"| {label}, {family} | " + " | ".join(row) + " |")
    print(f"\n(percentages against MPM at {cells[-1] * 1e3:g} mm; KE: kinetic over chemical energy at the end)")


if __name__ == "__main__":
    main()
