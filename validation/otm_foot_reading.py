#!/usr/bin/python3
"""The foot of a Taylor bar read from its final particle file in several ways, to tell where two
discretisations of the same bar differ: in the body (how much volume lies at which radius) or only
in the last layer of points at the rim, which the `max_radius` probe reads.

docs/validation.md, "3D from a tetrahedral mesh" ("The bodies agree; their rims do not"). The bar's
axis is y through x = z = 0 and it stands on the anvil at y = 0 (examples/taylor_bar_otm_3d_mesh.yaml,
a quarter bar; a whole bar or a half is recognised from the points' signs). Per run folder:

- slab radius: the volume-equivalent radius of each slab [a, b) along the axis. Each point's
  current volume is spread evenly over its domain's height, the half-height along y of the domain
  F [-h, h] being sum_j |F_yj| h_j; the slab's volume over its height is the cross-section's area,
  taken as the bar's sector of a disc: r = sqrt(A / (sector pi)).
- r50, r90: the radii within which 50 and 90 % of the volume of the points centred within `band`
  of the anvil lies (points sorted by centre radius).
- outermost centre: the largest centre radius among those points.
- corner radius: what the probe reads, the largest distance from the axis of the corners
  x + F (+-h) of the same points.
- corner radius by angle: the same largest corner distance within each 10 degree sector of the
  points' centres (sectors of [-180, 180) degrees about the axis, from the x axis towards z),
  averaged over the sectors that hold points: a round foot's radius whatever its ripple, where the
  largest over all angles reads the ripple's crest.
- surface carried (with --radius R, the bar's radius at the start): where the bar's initial surface
  went, x + F (R - |X|) e_r from each point of the band that started within 0.5 mm of the surface
  (X its position in the first particle file, e_r the radial direction there; first order in the
  distance), the largest over those points; the points must be the same in both files (no
  adaptivity, no deletion). It tells a rim that lies further out because the points were placed
  nearer the surface from one whose material moved further.
- hoop consistency (with --radius): in an axisymmetric motion a point's hoop line element
  stretches by exactly r / R (its distance from the axis now over at the start), so
  q = (r / R) / |F E_theta| is 1 for every point whose position and F agree; the median of q over
  the band's points in bands of R (fractions 0.1-0.3-0.6-0.8-0.95-1 of the largest R) tells points
  that spread further (or less) than their own F says.
- angular drift (with --radius): how far about the axis the rim's points moved, theta - Theta in
  degrees (their angle now minus that in the first file), the median over the band's points that
  started beyond 0.6 of the largest R, per 10 degree sector of the start angle folded into
  [0, 90) (a lattice's axes repeat every 90 degrees). An axisymmetric motion moves no point about
  the axis: a drift tells material gathering at some angles.
- corner at the start (with --radius): the corner radius of the same band in the first file, and
  the final one over it: the probe's spread, free of where each seeding's domains reach at the start.

  /usr/bin/python3 validation/otm_foot_reading.py out/otm_mesh_lattice/mesh out/otm_mesh_lattice/cut_lattice
"""
import argparse
import glob
import itertools
import math
import os

import h5py
import numpy as np


def particle_files(run_dir):
    files = sorted(glob.glob(os.path.join(run_dir, "particles_*.h5")))
    if not files:
        raise SystemExit(f"{run_dir}: no particles_*.h5 (not a run folder, or no output written)")
    return files


def final_particle_file(run_dir):
    return particle_files(run_dir)[-1]


def first_particle_file(run_dir):
    return particle_files(run_dir)[0]


def load(path):
    with h5py.File(path, "r") as f:
        return {"x": f["x"][:], "volume": f["volume"][:], "F": f["F"][:].reshape(-1, 3, 3),
                "half": f["half_size"][:], "time": float(f["time"][()])}


def sector_of(x, tol=1e-12):
    """The bar's share of a full disc: 1/4 if every point has x, z >= 0, 1/2 if one of them is
    signed, 1 otherwise (the decks' symmetry planes are x = 0 and z = 0)."""
    quarter_x, quarter_z = np.all(x[:, 0] >= -tol), np.all(x[:, 2] >= -tol)
    return 0.25 if quarter_x and quarter_z else 0.5 if quarter_x or quarter_z else 1.0


def slab_radii(p, edges, sector):
    """Volume-equivalent radius (m) of each slab between successive `edges` (m along y)."""
    hy = np.sum(np.abs(p["F"][:, 1, :] * p["half"]), axis=1)
    lo, hi = p["x"][:, 1] - hy, p["x"][:, 1] + hy
    height = np.maximum(hi - lo, np.finfo(float).tiny)
    radii = []
    for a, b in zip(edges[:-1], edges[1:]):
        share = np.clip((np.minimum(hi, b) - np.maximum(lo, a)) / height, 0.0, 1.0)
        area = float(np.sum(p["volume"] * share)) / (b - a)
        radii.append(math.sqrt(area / (sector * math.pi)))
    return radii


def foot_measures(p, band):
    """r50, r90, the outermost centre and the probe's corner radius (m) of the points centred
    within `band` of the anvil."""
    near = p["x"][:, 1] < band
    if not near.any():
        raise SystemExit(f"no point is centred within {band * 1e3:g} mm of the anvil")
    x, vol = p["x"][near], p["volume"][near]
    r = np.hypot(x[:, 0], x[:, 2])
    order = np.argsort(r, kind="stable")
    cumulative = np.cumsum(vol[order]) / vol.sum()
    quantile = {q: float(r[order][np.searchsorted(cumulative, q)]) for q in (0.5, 0.9)}
    point_corner = np.zeros(len(x))  # each point's farthest corner from the axis
    for s in itertools.product((-1.0, 1.0), repeat=3):
        c = x + np.einsum("pij,pj->pi", p["F"][near], p["half"][near] * np.array(s))
        point_corner = np.maximum(point_corner, np.hypot(c[:, 0], c[:, 2]))
    sector = np.floor((np.degrees(np.arctan2(x[:, 2], x[:, 0])) + 180.0) / 10.0).astype(int)
    by_sector = [point_corner[sector == k].max() for k in np.unique(sector)]
    return {"r50": quantile[0.5], "r90": quantile[0.9], "outermost_centre": float(r.max()),
            "corner": float(point_corner.max()), "corner_by_angle": float(np.mean(by_sector))}


def same_points(p0, p, reading):
    """The start and end positions, refused when the two files hold different points (adaptivity,
    deletion): readings that follow each point from the first file to the last."""
    if len(p0["x"]) != len(p["x"]):
        raise SystemExit(f"{reading}: the first and last particle files hold different points")
    return p0["x"], p["x"]


def surface_carried(p0, p, band, radius, start_within=0.5e-3):
    """The largest radius (m) the initial surface r = radius reaches, carried by F from the points
    centred within `band` of the anvil now that started within `start_within` of the surface."""
    X, x = same_points(p0, p, "surface carried")
    r0 = np.hypot(X[:, 0], X[:, 2])
    use = (x[:, 1] < band) & (r0 > radius - start_within) & (r0 > 0)
    e = np.c_[X[use, 0] / r0[use], np.zeros(use.sum()), X[use, 2] / r0[use]]
    s = x[use] + np.einsum("pij,pj->pi", p["F"][use], (radius - r0[use])[:, None] * e)
    return float(np.hypot(s[:, 0], s[:, 2]).max())


HOOP_BANDS = (0.1, 0.3, 0.6, 0.8, 0.95, 1.0)


def hoop_consistency(p0, p, band):
    """The median of q = (r / R) / |F E_theta| over the points centred within `band` of the anvil,
    per band of their start radius R (HOOP_BANDS, fractions of the largest R); None for an empty band."""
    X, x = same_points(p0, p, "hoop consistency")
    R = np.hypot(X[:, 0], X[:, 2])
    r = np.hypot(x[:, 0], x[:, 2])
    edges = np.array(HOOP_BANDS) * R.max()
    use = (x[:, 1] < band) & (R >= edges[0])
    e_theta = np.c_[-X[use, 2] / R[use], np.zeros(use.sum()), X[use, 0] / R[use]]
    q = (r[use] / R[use]) / np.linalg.norm(np.einsum("pij,pj->pi", p["F"][use], e_theta), axis=1)
    medians = []
    for k, (lo, hi) in enumerate(zip(edges[:-1], edges[1:])):
        last = k == len(edges) - 2
        inside = (R[use] >= lo) & ((R[use] <= hi) if last else (R[use] < hi))
        medians.append(float(np.median(q[inside])) if inside.any() else None)
    return medians


DRIFT_OUTER = 0.6  # the rim's points: started beyond this fraction of the largest start radius


def angular_drift(p0, p, band, outer=DRIFT_OUTER):
    """The median of theta - Theta (degrees) over the points centred within `band` of the anvil that
    started beyond `outer` of the largest start radius, per 10 degree sector of Theta folded into
    [0, 90); None for an empty sector."""
    X, x = same_points(p0, p, "angular drift")
    R = np.hypot(X[:, 0], X[:, 2])
    start = np.degrees(np.arctan2(X[:, 2], X[:, 0]))
    drift = (np.degrees(np.arctan2(x[:, 2], x[:, 0])) - start + 180.0) % 360.0 - 180.0
    use = (x[:, 1] < band) & (R >= outer * R.max())
    folded = start % 90.0
    medians = []
    for lo in range(0, 90, 10):
        inside = use & (folded >= lo) & (folded < lo + 10)
        medians.append(float(np.median(drift[inside])) if inside.any() else None)
    return medians


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="run folders (their last particles_*.h5 is read); the first is the reference")
    ap.add_argument("--slab", type=float, default=1.0, help="slab height, mm (default 1)")
    ap.add_argument("--slabs", type=int, default=8, help="number of slabs from the anvil (default 8)")
    ap.add_argument("--band", type=float, default=0.5, help="the foot's band above the anvil, mm (default 0.5, the probe's)")
    ap.add_argument("--radius", type=float, help="the bar's radius at the start, mm: also read where its surface went")
    a = ap.parse_args()
    edges = np.arange(a.slabs + 1) * a.slab * 1e-3
    rows = []
    for run in a.runs:
        p = load(final_particle_file(run))
        measures = foot_measures(p, a.band * 1e-3)
        hoop = drift = None
        if a.radius:
            p0 = load(first_particle_file(run))
            measures["surface_carried"] = surface_carried(p0, p, a.band * 1e-3, a.radius * 1e-3)
            measures["corner_at_start"] = foot_measures(p0, a.band * 1e-3)["corner"]
            hoop = hoop_consistency(p0, p, a.band * 1e-3)
            drift = angular_drift(p0, p, a.band * 1e-3)
        rows.append((run, p["time"], slab_radii(p, edges, sector_of(p["x"])), measures, hoop, drift))
    ref = rows[0]

    def vs(value, reference):
        return f" ({100 * (value / reference - 1):+.1f} %)" if reference > 0 and value is not reference else ""

    print(f"slab radius, mm (slabs of {a.slab:g} mm from the anvil; in brackets against {ref[0]}):")
    for run, t, radii, _, _, _ in rows:
        cells = "  ".join(f"{r * 1e3:.3f}{vs(r, r0)}" for r, r0 in zip(radii, ref[2]))
        print(f"  {run} (t = {t * 1e6:.2f} us): {cells}")
    print(f"points centred within {a.band:g} mm of the anvil, mm:")
    for run, _, _, m, _, _ in rows:
        print(f"  {run}: " + "  ".join(f"{k} {v * 1e3:.3f}{vs(v, ref[3][k])}" for k, v in m.items()))
        if "corner_at_start" in m:
            spread = m["corner"] / m["corner_at_start"]
            against = "" if run == ref[0] else vs(spread, ref[3]["corner"] / ref[3]["corner_at_start"])
            print(f"    corner over its start: {spread:.4f}{against}")
    if a.radius:
        bands = ", ".join(f"{lo:g}-{hi:g}" for lo, hi in zip(HOOP_BANDS[:-1], HOOP_BANDS[1:]))
        print(f"hoop consistency (r/R over |F E_theta|, median per band of R as a fraction of the largest: {bands}):")
        for run, _, _, _, hoop, _ in rows:
            print(f"  {run}: " + "  ".join("-" if q is None else f"{q:.3f}" for q in hoop))
        print("angular drift (theta now minus at the start, degrees; median over the rim's points that started beyond "
              f"{DRIFT_OUTER:g} of the largest R, per 10 degree sector of the start angle folded into 0-90):")
        for run, _, _, _, _, drift in rows:
            print(f"  {run}: " + "  ".join("-" if d is None else f"{d:+.2f}" for d in drift))


if __name__ == "__main__":
    main()
