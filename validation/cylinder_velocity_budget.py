#!/usr/bin/python3
"""Where the exploding cylinder's case velocity goes: the seed's tube in axisymmetric MPM (continuum
products, no fracture), from Gurney's infinite tube to the finite tube lit at one end.

Runs the tube of examples/exploding_cylinder_pd.yaml (the LX-14 stand-in for PBXN-9 in a 4340 case,
outer radius 16.13 mm) as axisymmetric MPM, the deck of tests/verification/sliding_detonation_support.hpp,
in four forms, and prints the case's mass-weighted radial velocity:
  long tube, no strength   392 mm, yield stress 1 MPa: the steady section far from both ends at
                           50-60 us, against Gurney's cylinder (2970 m/s (M/C + 1/2)^-1/2: Cooper,
                           Explosives Engineering, 1996)
  long tube, J2 750 MPa    the same with the case's strength (the seed's base case), unbroken
  example tube             98 mm, 1.00 in bore: the middle third at 25 us
  timing tube              108 mm, the bore from the case's 239.9 g (validation/exploding_cylinders.py
                           --tube seed_timing): the middle third at 25 us
The finite tubes at 0.43 mm cells: at 0.86 mm the two bores seed the same particles.

Usage: validation/cylinder_velocity_budget.py --ballista build/ballista --out DIR
"""
import argparse
import glob
import os
import subprocess

import h5py
import numpy as np

from case_velocity_thirds import case_thirds
from exploding_cylinders import OUTER_RADIUS as OUTER, TIMING_LENGTH, timing_bore

GURNEY_SQRT_2E = 2970.0  # m/s, LX-14 (data/materials.yaml, lx14_pbxn9_standin)


def deck(length, bore, yield_stress, end_time, cell, r_max):
    return f"""simulation: {{solver: mpm, dimension: axisymmetric, end_time: {end_time}, cfl: 0.3, on_particle_exit: delete}}
materials:
  steel_4340: {{model: j2_plasticity, density: 7850, bulk_modulus: 140.3e9, shear_modulus: 70e9, yield_stress: {yield_stress}}}
  pbxn9: {{preset: lx14_pbxn9_standin}}
mpm: {{shape_function: gimp, update: musl, flip: 0.99}}
grid: {{lower: [0.0, -0.03], upper: [{r_max}, {length + 0.03}], cell_size: {cell}}}
bodies:
  - {{name: case, material: steel_4340, particles_per_cell: 2, shape: {{type: tube, center: [0, 0, 0], axis: y, radius: {OUTER}, inner_radius: {bore}, length: {length}}}}}
  - {{name: charge, material: pbxn9, particles_per_cell: 2, shape: {{type: cylinder, center: [0, 0, 0], axis: y, radius: {bore}, length: {length}}}}}
detonation: {{points: [{{position: [0, 0], time: 0}}]}}
output: {{interval: {end_time / 6}, fields: [v, body]}}
"""


def steady_section(run_dir, z_lo, z_hi):
    """Mass-weighted radial velocity of the case between axial z_lo and z_hi in the last file."""
    with h5py.File(sorted(glob.glob(run_dir + "/particles_*.h5"))[-1]) as f:
        x, v, body = f["x"][:], f["v"][:], f["body"][:]
    s = (body == 0) & (x[:, 1] >= z_lo) & (x[:, 1] < z_hi)
    return float(np.sum(x[s, 0] * v[s, 0]) / np.sum(x[s, 0]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ballista", default="build/ballista")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    bore_timing = timing_bore("4340_HT1_PBXN9")
    cases = [  # name, length, bore, yield stress, end time, cell
        ("long_no_strength", 0.392, 12.7e-3, 1e6, 60e-6, 0.86e-3),
        ("long_j2", 0.392, 12.7e-3, 750e6, 60e-6, 0.86e-3),
        ("example_tube", 0.098, 12.7e-3, 750e6, 25e-6, 0.43e-3),
        ("timing_tube", TIMING_LENGTH, bore_timing, 750e6, 25e-6, 0.43e-3),
    ]
    print("| tube | M/C | Gurney | case velocity | where |")
    print("|---|---|---|---|---|")
    for name, length, bore, ys, end, cell in cases:
        path = os.path.join(a.out, name + ".yaml")
        with open(path, "w") as f:
            f.write(deck(length, bore, ys, end, cell, 0.15 if end > 30e-6 else 0.07))
        run_dir = os.path.join(a.out, name)
        if not os.path.exists(os.path.join(run_dir, "summary.json")):
            subprocess.run([a.ballista, "run", path, "-o", run_dir, "--overwrite", "-q", "--no-plots"], check=True)
        mc = 7850 * (OUTER ** 2 - bore ** 2) / (1835 * bore ** 2)
        gurney = GURNEY_SQRT_2E / np.sqrt(mc + 0.5)
        if length > 0.2:  # the detonation reaches 0.39 m at 45 us: 0.20-0.30 m is 20-40 us behind it at 60 us
            vel, where = steady_section(run_dir, 0.20, 0.30), "0.20-0.30 m at 60 us"
        else:
            vel, where = case_thirds(run_dir, length)[3][1][1], "middle third at 25 us"
        print(f"| {name} ({length * 1e3:.0f} mm, bore {2e3 * bore:.2f} mm, yield {ys / 1e6:g} MPa) | {mc:.2f} | "
              f"{gurney:.0f} m/s | {vel:.0f} m/s | {where} |")


if __name__ == "__main__":
    main()
