#!/usr/bin/python3
"""Radial velocity of a tube's case by thirds of its length, from a Ballista run's last particle file.

The exploding cylinder (examples/exploding_cylinder_pd.yaml, 3D peridynamics, tube along z) or the
same tube in axisymmetric MPM (x the radius, y the axis): the mass-weighted radial velocity of the
case (body 0) over the first, middle and last third of the tube's length, by current axial
position. The run must write the fields v and body (--set 'output.fields=[v,body]'); 3D points
weigh alike (one lattice), axisymmetric particles by their radius (mass per radian). Used for
docs/validation.md "Why the case was slow".

The flash X-ray's velocity (seed 001, "Explosive Testing"): the seed divides a horizontal flight
distance by a flight time, the X-ray's time less the detonator's 3 us and 6.426 us for the shock to
reach the charge's centre, so its figure is a mean over the flight, acceleration included, and not
the case's velocity at the X-ray. The like-for-like figure of a run is the same arithmetic on its own
flight: the middle third's mean radius at the last file less its mean radius at t = 0, over
the run's time less 6.426 us (t = 0 is the detonator's output).

Usage: validation/case_velocity_thirds.py RUN_DIR [--length 0.098] [--json FILE]
"""
import argparse
import glob
import json
import sys

import h5py
import numpy as np


THIRDS = (("first", 0, 1 / 3), ("middle", 1 / 3, 2 / 3), ("last", 2 / 3, 1))
SEED_FLIGHT_START = 6.426e-6  # s after the detonator's output: seed 001's shock arrival at the charge's centre


def case_thirds(run_dir, length=0.098, index=-1):
    """The case by thirds in a particle file (the last by default, `index` into the sorted files):
    (time s, 3D or not, case points, [(name, mass-weighted radial velocity m/s, mean radius m)] for
    the first, middle and last third). Raises ValueError when the run has no particle file or did
    not write the field body."""
    files = sorted(glob.glob(run_dir + "/particles_*.h5"))
    if not files:
        raise ValueError(f"no particle files in {run_dir}")
    with h5py.File(files[index]) as f:
        if "body" not in f:
            raise ValueError("the run did not write the field body: --set 'output.fields=[v,body]'")
        x, v, body, t = f["x"][:], f["v"][:], f["body"][:], f["time"][()]
    case = body == 0
    x, v = x[case], v[case]
    three_d = bool(np.any(x[:, 2] != 0.0))
    if three_d:
        r = np.hypot(x[:, 0], x[:, 1])
        vr = (x[:, 0] * v[:, 0] + x[:, 1] * v[:, 1]) / r
        z, w = x[:, 2], np.ones(len(r))
    else:
        r, vr, z, w = x[:, 0], v[:, 0], x[:, 1], x[:, 0]
    thirds = []
    for name, lo, hi in THIRDS:
        s = (z >= lo * length) & (z < hi * length)
        thirds.append((name, float(np.sum(w[s] * vr[s]) / np.sum(w[s])), float(r[s].mean())))
    return t, three_d, len(r), thirds


def seed_flight_velocity(run_dir, length=0.098):
    """The seed's X-ray arithmetic applied to a run (module docstring): (flight distance m, flight
    time s, velocity m/s) of the middle third, from its mean radius in the last particle file and in
    the first (t = 0)."""
    t0, _, _, start = case_thirds(run_dir, length, 0)
    t, _, _, thirds = case_thirds(run_dir, length)
    if t0 != 0.0 or t <= SEED_FLIGHT_START:
        raise ValueError(f"{run_dir}: the flight needs the particle file at t = 0 and one after {SEED_FLIGHT_START} s")
    distance = thirds[1][2] - start[1][2]
    flight_time = t - SEED_FLIGHT_START
    return distance, flight_time, distance / flight_time


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir")
    ap.add_argument("--length", type=float, default=0.098, help="tube length, m (it starts at axial 0)")
    ap.add_argument("--json", help="also write the numbers to this file (`ballista validate` reads it)")
    a = ap.parse_args()
    try:
        t, three_d, n, thirds = case_thirds(a.run_dir, a.length)
    except ValueError as e:
        sys.exit(str(e))
    try:
        flight = seed_flight_velocity(a.run_dir, a.length)
    except ValueError as e:
        flight = None
        print(f"no flight velocity: {e}")
    if a.json:
        with open(a.json, "w", encoding="utf-8") as f:
            json.dump({"time": float(t), "case_points": int(n), "three_d": three_d,
                       "thirds": {name: {"velocity": vel, "mean_radius": radius} for name, vel, radius in thirds},
                       "seed_flight": None if flight is None else
                       {"distance": flight[0], "time": flight[1], "velocity": flight[2]}}, f)
    print(f"t = {t * 1e6:.2f} us, {'3D' if three_d else 'axisymmetric'}, {n} case points")
    for name, vel, radius in thirds:
        print(f"{name:6s} third: {vel:7.0f} m/s, mean radius {1e3 * radius:.1f} mm")
    if flight:
        print(f"middle third's flight as the seed's X-ray reads it: {1e3 * flight[0]:.1f} mm in "
              f"{1e6 * flight[1]:.2f} us, {flight[2]:.0f} m/s")


if __name__ == "__main__":
    main()
