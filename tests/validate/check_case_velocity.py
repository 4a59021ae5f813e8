#!/usr/bin/python3
"""validation/case_velocity_thirds.py on run folders written by hand: a 3D tube and an axisymmetric
one whose case flies out at a known radial velocity V from the seed's flight start (6.426 us), the
charge (body 1) at rest. The seed's X-ray arithmetic on such a flight is V exactly (distance V (t -
6.426 us) over the same time), and so is the middle third's mass-weighted radial velocity; a charge
point counted as case, or the wrong file read for t = 0, moves either figure by far more than the
round-off bound 1e-9 relative."""
import os
import sys

import h5py
import numpy as np

import script_args

V, T_END, T_START = 1500.0, 97.78e-6, 6.426e-6
LENGTH, RO, RI = 0.098, 16.13e-3, 12.7e-3


def write(run_dir, three_d):
    os.makedirs(run_dir, exist_ok=True)
    rng = np.random.default_rng(7)
    n = 3000
    r0 = np.sqrt(rng.uniform(RI ** 2, RO ** 2, n))  # uniform in the wall's area
    theta, z = rng.uniform(0, 2 * np.pi, n), rng.uniform(0, LENGTH, n)
    charge_r = rng.uniform(0, RI, 500)
    for i, t in enumerate((0.0, T_END)):
        r = r0 + (V * (t - T_START) if t > 0 else 0.0)
        if three_d:
            x = np.c_[r * np.cos(theta), r * np.sin(theta), z]
            v = np.c_[V * np.cos(theta), V * np.sin(theta), 0 * z] * (t > 0)
            xc = np.c_[charge_r, 0 * charge_r, rng.uniform(0, LENGTH, 500)]
        else:  # axisymmetric: x the radius, y the axis
            x, v = np.c_[r, z, 0 * z], np.c_[np.full(n, V * (t > 0)), 0 * z, 0 * z]
            xc = np.c_[charge_r, rng.uniform(0, LENGTH, 500), 0 * charge_r]
        with h5py.File(os.path.join(run_dir, f"particles_{i:06d}.h5"), "w") as f:
            f["x"] = np.r_[x, xc]
            f["v"] = np.r_[v, np.full((500, 3), 9e3)]  # a fast charge: counted as case, it shows
            f["body"] = np.r_[np.zeros(n, dtype=np.int32), np.ones(500, dtype=np.int32)]
            f["time"] = t


def main():
    a = script_args.parse()
    from case_velocity_thirds import case_thirds, seed_flight_velocity
    failures = 0
    for three_d in (True, False):
        run_dir = os.path.join(a.out, "tube_3d" if three_d else "tube_axisymmetric")
        write(run_dir, three_d)
        distance, flight_time, velocity = seed_flight_velocity(run_dir, LENGTH)
        middle = case_thirds(run_dir, LENGTH)[3][1][1]
        ok = abs(velocity / V - 1) < 1e-9 and abs(middle / V - 1) < 1e-9 and abs(flight_time - (T_END - T_START)) < 1e-15
        print(f"{os.path.basename(run_dir)}: flight {distance * 1e3:.3f} mm in {flight_time * 1e6:.3f} us, "
              f"{velocity:.6f} m/s; middle third {middle:.6f} m/s (exact {V}): {'ok' if ok else 'FAIL'}")
        failures += not ok
    # EMU's ring (exploding_cylinders.EMU_RING_IN): 13.1 in across for 4340 HT1 is a radial flight of
    # (13.1 in - the tube's 32.26 mm) / 2 = 150.24 mm; an inch or diameter/radius slip moves it by
    # far more than the 0.01 mm allowed (the figure the docs quote to 0.1 mm).
    from exploding_cylinders import emu_flight_mm
    emu = emu_flight_mm("4340_HT1_PBXN9")
    ok = abs(emu - (13.1 * 25.4 - 32.26) / 2) < 0.01 and emu_flight_mm("1018_TNT") is None
    print(f"EMU's 4340 HT1 ring: flight {emu:.3f} mm (exact 150.240): {'ok' if ok else 'FAIL'}")
    failures += not ok
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
