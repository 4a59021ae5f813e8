#!/usr/bin/python3
"""validation/otm_foot_reading.py on a bar written by hand with known answers.

A quarter cylinder of radius R = 3.2 mm and height 8 mm, as n = 25 rings of equal area (ring k
between R sqrt(k/n) and R sqrt((k+1)/n), its points at R sqrt((k+1/2)/n)) times 9 points by angle,
in layers 0.25 mm high starting 0.1 mm below the anvil so that domains straddle the slabs' edges.
Each point's volume is its share of the quarter disc times the layer's height, and its domain is
F [-h, h] with F = diag(1, 1/2, 1) and h_y = a layer's height (a half-height of half a layer: the
domains tile y exactly). So:
- every 1 mm slab from y = 0 holds exactly its height times the quarter disc's area: its
  volume-equivalent radius is R (to round-off, 1e-12 relative); the same bar mirrored to a half
  bar (z of both signs) is recognised as one and gives R again; a wrong spreading of the domains
  over the slabs (h_y without F) or a wrong sector moves it by far more;
- r50 and r90 among the points centred within 0.5 mm fall inside rings 12 and 22 (cumulative
  volume 0.48-0.52 and 0.88-0.92: not at a ring's edge), so they are those rings' radii exactly;
- the outermost centre is ring 24's radius, and the corner radius is the largest of
  |(r cos t + a, r sin t + a)| over the points (a = h_x = h_z), written out here independently;
- the corner radius by angle: the 9 angles sit at the centres of the 10 degree sectors from 0 to
  90 degrees, one per sector, so it is the mean over the angles of ring 24's largest corner
  |(r cos t + a, r sin t + a)| (a sector's points mixed with its neighbour's, or the mean taken over
  empty sectors, moves it by far more than 1e-12);
- the surface carried: the same quarter bar written again at t = 0 and stretched radially by
  lambda = 2.3 at the end (x = lambda X across, F = diag(lambda, 1, lambda)), so that every point
  carries the initial surface r = R to exactly lambda R (x + F (R - r) e_r = lambda R e_r); a wrong
  file for the start, a missing F or the distance taken from the wrong radius moves it by far more;
- the hoop consistency of the same stretched bar: r / R = |F E_theta| = lambda for every point, so
  q = 1 in every band of R (to round-off); and with the positions spread a further 10 % radially
  while F stays (x = 1.1 lambda X across), q = 1.1 in every band: the axial stretch (1) read in
  place of the hoop's (lambda), or the two files swapped, moves it off by a factor of lambda or more;
- the angular drift of the same stretched bar: zero in every sector (a radial motion); and with the
  final positions turned about the axis by delta sin(4 Theta) (delta = 3 degrees: a four-fold
  gathering, as on a lattice), each 10 degree sector's median is delta sin(4 Theta_k) at its one
  angle Theta_k, to round-off (the files swapped, or the drift in radians, moves it by far more);
- the corner at the start: the stretched bar's first file is the unstretched bar, so it is the
  corner radius above."""
import math
import os
import sys

import h5py
import numpy as np

import script_args

R, N_RING, N_ANGLE, LAYER, A = 3.2e-3, 25, 9, 0.25e-3, 0.05e-3


def ring_radius(k):
    return R * math.sqrt((k + 0.5) / N_RING)


def write_bar(run_dir, half_bar):
    os.makedirs(run_dir, exist_ok=True)
    rings = np.repeat(np.arange(N_RING), N_ANGLE)
    theta = np.tile((np.arange(N_ANGLE) + 0.5) * (math.pi / 2) / N_ANGLE, N_RING)
    r = np.array([ring_radius(k) for k in rings])
    ys = -0.1e-3 + LAYER * (np.arange(34) + 0.5)  # layers from -0.1 to 8.4 mm
    x = np.concatenate([np.c_[r * np.cos(theta), np.full(r.size, y), r * np.sin(theta)] for y in ys])
    volume = np.full(len(x), (math.pi * R * R / 4) / (N_RING * N_ANGLE) * LAYER)
    if half_bar:
        x = np.r_[x, x * np.array([1.0, 1.0, -1.0])]
        volume = np.r_[volume, volume]
    F = np.tile(np.diag([1.0, 0.5, 1.0]).ravel(), (len(x), 1))
    half = np.tile([A, LAYER, A], (len(x), 1))
    with h5py.File(os.path.join(run_dir, "particles_000001.h5"), "w") as f:
        f["x"], f["volume"], f["F"], f["half_size"], f["time"] = x, volume, F, half, 80e-6
    # An earlier output that must not be the one read.
    with h5py.File(os.path.join(run_dir, "particles_000000.h5"), "w") as f:
        f["x"], f["volume"], f["F"], f["half_size"], f["time"] = x * 2, volume, F, half, 0.0


def main():
    a = script_args.parse()
    from otm_foot_reading import (angular_drift, final_particle_file, first_particle_file, foot_measures,
                                  hoop_consistency, load, sector_of, slab_radii, surface_carried)
    failures = []
    edges = np.arange(9) * 1e-3
    for half_bar in (False, True):
        run = os.path.join(a.out, "half_bar" if half_bar else "quarter_bar")
        write_bar(run, half_bar)
        p = load(final_particle_file(run))
        sector = sector_of(p["x"])
        radii = slab_radii(p, edges, sector)
        worst = max(abs(r / R - 1) for r in radii)
        print(f"{os.path.basename(run)}: sector {sector}, slab radii within {worst:.1e} of R")
        if sector != (0.5 if half_bar else 0.25) or worst > 1e-12:
            failures.append(f"{run}: sector {sector}, slab radii {radii}")
    m = foot_measures(load(final_particle_file(os.path.join(a.out, "quarter_bar"))), 0.5e-3)
    theta = (np.arange(N_ANGLE) + 0.5) * (math.pi / 2) / N_ANGLE
    corner = max(math.hypot(ring_radius(k) * math.cos(t) + A, ring_radius(k) * math.sin(t) + A)
                 for k in range(N_RING) for t in theta)
    by_angle = np.mean([max(math.hypot(ring_radius(k) * math.cos(t) + A, ring_radius(k) * math.sin(t) + A)
                            for k in range(N_RING)) for t in theta])
    expected = {"r50": ring_radius(12), "r90": ring_radius(22), "outermost_centre": ring_radius(24), "corner": corner,
                "corner_by_angle": by_angle}
    # The surface carried by a homogeneous radial stretch.
    stretched = os.path.join(a.out, "stretched_bar")
    os.makedirs(stretched, exist_ok=True)
    write_bar(stretched, False)
    lam = 2.3
    with h5py.File(os.path.join(stretched, "particles_000001.h5"), "r") as f:
        X, volume, half = f["x"][:], f["volume"][:], f["half_size"][:]
    with h5py.File(os.path.join(stretched, "particles_000000.h5"), "w") as f:
        f["x"], f["volume"], f["F"], f["half_size"], f["time"] = X, volume, np.tile(np.eye(3).ravel(), (len(X), 1)), half, 0.0
    with h5py.File(os.path.join(stretched, "particles_000001.h5"), "w") as f:
        f["x"] = X * np.array([lam, 1.0, lam])
        f["volume"], f["half_size"], f["time"] = volume * lam * lam, half, 80e-6
        f["F"] = np.tile(np.diag([lam, 1.0, lam]).ravel(), (len(X), 1))
    p0, p1 = load(first_particle_file(stretched)), load(final_particle_file(stretched))
    m["surface_carried"] = surface_carried(p0, p1, 0.5e-3, R)
    expected["surface_carried"] = lam * R
    for spread in (1.0, 1.1):
        p1_spread = dict(p1, x=p1["x"] * np.array([spread, 1.0, spread]))
        hoop = hoop_consistency(p0, p1_spread, 0.5e-3)
        ok = all(q is not None and abs(q / spread - 1) < 1e-12 for q in hoop)
        print(f"hoop consistency, positions spread {spread:g}: {hoop}: {'ok' if ok else 'FAIL'}")
        if not ok:
            failures.append(f"hoop consistency at spread {spread}")
    m["corner_at_start"] = foot_measures(p0, 0.5e-3)["corner"]
    expected["corner_at_start"] = corner
    delta = 3.0
    for turn in (0.0, delta):
        start = np.arctan2(p0["x"][:, 2], p0["x"][:, 0])
        r1 = np.hypot(p1["x"][:, 0], p1["x"][:, 2])
        angle = start + np.radians(turn * np.sin(4 * start))
        p1_turned = dict(p1, x=np.c_[r1 * np.cos(angle), p1["x"][:, 1], r1 * np.sin(angle)])
        drift = angular_drift(p0, p1_turned, 0.5e-3)
        want = [turn * math.sin(4 * t) for t in theta]
        ok = all(d is not None and abs(d - w) < 1e-9 for d, w in zip(drift, want))
        print(f"angular drift, turned by {turn:g} sin(4 Theta) degrees: {[round(d, 6) for d in drift]}: "
              f"{'ok' if ok else 'FAIL'}")
        if not ok:
            failures.append(f"angular drift at {turn}")
    for key, value in expected.items():
        ok = abs(m[key] / value - 1) < 1e-12
        print(f"{key}: {m[key] * 1e3:.6f} mm (expected {value * 1e3:.6f}): {'ok' if ok else 'FAIL'}")
        if not ok:
            failures.append(key)
    if failures:
        print("FAILED:", "; ".join(failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
