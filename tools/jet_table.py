#!/usr/bin/python3
"""The jet of a shaped-charge formation run as a `jet:` segment table for a perforation deck.

Reads one particle file of an axisymmetric run (x = radius, y = axis, the jet flying towards +y;
e.g. examples/shaped_charge_jet_formation.yaml), takes the liner's points faster than --min-speed
(the jet; the slug and the liner's rear stay behind), cuts the jet into --segments pieces of equal
mass along the axis (each cut halfway between the two points it separates) and writes one row per
piece, tip first, in the CSV format that a deck's
`jet: {file: ...}` reads (docs/deck.md, "Rods and jets"):

    radius, length, velocity, insert_time        (m, m, m/s, s)

- velocity: the piece's centre-of-mass axial velocity, sum m v / sum m;
- length: the distance between the piece's cuts (the tip piece from the tip point, the tail piece to
  the tail point: the pieces tile the jet's extent);
- radius: that of a solid cylinder of the piece's mass and length at the liner's density,
  r = sqrt(M / (rho pi L)), M = 2 pi sum m (the particles' masses are per radian): the piece's
  mass, which is what a target stops, is kept, not its shape (a stretching jet is not a cylinder);
- insert_time: when the piece's leading face crossed the charge plane --plane (m, on the axis) in
  free flight, t - (y_lead - plane) / v, relative to the first row's. A deck that reads the table
  places every piece where the free flight from the charge plane puts it (its `standoff` from the
  plane to the target's face), so the pieces' spacing at the target follows from their velocities.

The table keeps the jet's mass, axial momentum and axial kinetic energy (each piece's M, M v and
M v^2 / 2 summed); what it drops is each piece's internal velocity spread (reported: the kinetic
energy of the velocities about the pieces' means, as a share of the jet's) and the jet's radial
motion and internal energy.

Usage: tools/jet_table.py RUN_DIR --out jet.csv [--time T] [--segments 10] [--min-speed 2000]
       [--plane 0.036] [--body liner]
"""
import argparse
import glob
import math
import os

import h5py
import numpy as np
import yaml


def particle_file(run, time):
    files = sorted(glob.glob(os.path.join(run, "particles_*.h5")))
    if not files:
        raise SystemExit(f"no particle files in {run}")
    if time is None:
        return files[-1]
    def distance(fn):
        with h5py.File(fn) as f:
            return abs(f["time"][()] - time)
    return min(files, key=distance)


def jet_table(run, time=None, segments=10, min_speed=2000.0, plane=None, body=None):
    """(rows, report): rows of [radius, length, velocity, insert_time]; the report of what the
    table keeps and drops."""
    deck = yaml.safe_load(open(os.path.join(run, "resolved.yaml")))
    if deck["simulation"]["dimension"] != "axisymmetric":
        raise SystemExit("the run must be axisymmetric (x = radius, y = axis)")
    names = [b["name"] for b in deck["bodies"]]
    liner = body or next((b["name"] for b in deck["bodies"] if b["shape"]["type"] == "liner"), None)
    if liner not in names:
        raise SystemExit(f"no body '{liner}' in the run (bodies: {', '.join(names)})")
    spec = deck["bodies"][names.index(liner)]
    rho = float(deck["materials"][spec["material"]]["density"])
    if plane is None:
        # Default charge plane: the liner's mouth (its shape's apex plus the cone's height).
        s = spec["shape"]
        if s["type"] != "liner":
            raise SystemExit("give --plane (the body is not a `liner` shape)")
        a = math.radians(0.5 * float(s["angle"]))
        plane = float(s["center"][1]) + 0.5 * float(s["diameter"]) / math.tan(a)
    fn = particle_file(run, time)
    with h5py.File(fn) as f:
        t = float(f["time"][()])
        sel = f["body"][:] == names.index(liner)
        y, vy, m = f["x"][:, 1][sel], f["v"][:, 1][sel], f["mass"][:][sel]
    jet = vy > min_speed
    if jet.sum() < segments:
        raise SystemExit(f"only {int(jet.sum())} points faster than {min_speed} m/s at t = {t:.3g} s")
    y, vy, m = y[jet], vy[jet], 2.0 * math.pi * m[jet]
    # Cut into pieces of equal mass, tip first: each cut halfway between the two points it separates,
    # so the pieces tile the jet from its tip point to its tail point and none is empty.
    order = np.argsort(-y)
    y, vy, m = y[order], vy[order], m[order]
    cum = np.cumsum(m)
    cuts, first = [y[0]], [0]
    for k in range(1, segments):
        i = int(np.searchsorted(cum, k * cum[-1] / segments))
        i = min(max(i + 1, first[-1] + 1), len(y) - (segments - k))
        first.append(i)
        cuts.append(0.5 * (y[i - 1] + y[i]))
    cuts.append(y[-1])
    first.append(len(y))
    rows, ke_spread = [], 0.0
    for k in range(segments):
        hi, lo = cuts[k], cuts[k + 1]
        piece = slice(first[k], first[k + 1])
        M = m[piece].sum()
        v = float(np.sum(m[piece] * vy[piece]) / M)
        ke_spread += 0.5 * float(np.sum(m[piece] * (vy[piece] - v) ** 2))
        L = hi - lo
        if not L > 0.0:
            raise SystemExit(f"piece {k} has no length (points at one position): use fewer --segments")
        rows.append([math.sqrt(M / (rho * math.pi * L)), L, v, t - (hi - plane) / v])
    t0 = rows[0][3]
    for r in rows:
        r[3] -= t0
    mass = float(m.sum())
    ke = 0.5 * float(np.sum(m * vy ** 2))
    report = {"file": fn, "time": t, "points": int(jet.sum()), "mass": mass, "momentum": float(np.sum(m * vy)),
              "kinetic_energy_axial": ke, "spread_share": ke_spread / ke, "plane": plane, "density": rho}
    return rows, report


def write_csv(rows, path):
    """The table as a deck's `jet: {file: ...}` reads it, every number at full precision."""
    with open(path, "w") as f:
        f.write("radius,length,velocity,insert_time\n")
        for r in rows:
            f.write(",".join(repr(x) for x in r) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("--out", required=True, help="CSV file to write")
    ap.add_argument("--time", type=float, help="time of the particle file to read, s (default: the last)")
    ap.add_argument("--segments", type=int, default=10)
    ap.add_argument("--min-speed", type=float, default=2000.0, help="m/s: slower liner points are not jet")
    ap.add_argument("--plane", type=float, help="charge plane on the axis, m (default: the liner's mouth)")
    ap.add_argument("--body", help="the liner body (default: the body with a `liner` shape)")
    a = ap.parse_args()
    rows, rep = jet_table(a.run, a.time, a.segments, a.min_speed, a.plane, a.body)
    with open(a.out, "w") as f:
        f.write(f"# jet of {rep['file']} at t = {rep['time']:.6g} s: {rep['points']} points faster than "
                f"{a.min_speed:g} m/s, {rep['mass'] * 1e3:.4g} g; charge plane y = {rep['plane']:.6g} m\n")
        f.write("radius,length,velocity,insert_time\n")
        for r in rows:
            f.write(",".join(f"{x:.6g}" for x in r) + "\n")
    print(f"{a.out}: {len(rows)} pieces, {rep['mass'] * 1e3:.4g} g, tip {rows[0][2]:.0f} m/s, tail {rows[-1][2]:.0f} m/s;"
          f" the velocity spread inside the pieces held {100 * rep['spread_share']:.2f} % of the jet's axial kinetic"
          f" energy (dropped)")


if __name__ == "__main__":
    main()
