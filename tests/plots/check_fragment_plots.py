#!/usr/bin/python3
"""Checks of the fragment statistics and figures of a run (tests/plots/CMakeLists.txt).

Runs `ballista run` on a tiny peridynamics deck of five separate boxes flying apart (bodies are
never bonded to each other, so each body is one fragment of known point count), then checks:
  summary    summary.json "fragments": count, largest/mean/total mass exact against the bodies'
             masses (points x density x cell volume), the Mott fit (N0, mu, r2) against an
             independent numpy fit of the same masses (MLE sqrt(mu) = mean sqrt(m); R^2 of
             ln N(>=m) against sqrt(m)); fragments.csv speeds equal the bodies' speeds
  figures    fragment_mass_distribution.png, fragment_velocity.png and (two snapshots)
             fragment_count.png are valid, non-blank PNGs
  two        a two-body deck with --no-plots: no PNG (those of an earlier run are cleared), mott_*
             left out with a reason; the script run by hand on it draws the mass figure without a
             fit and notes the skipped count figure
  empty      plot_fragments.py on a folder without fragments.csv: exit 2 naming fragments.csv
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_penetration_plots import check_png, fail  # noqa: E402

RHO, H = 2200.0, 1e-3  # kg/m^3, m (cell size = point spacing)
POINT_MASS = RHO * H ** 3
# name: (points along x, y, z), lower corner (m), velocity (m/s)
BODIES = {"a": ((4, 4, 4), (-0.010, 0.0, 0.0), (-5.0, 0.0, 0.0)),
          "b": ((2, 4, 4), (0.004, 0.0, 0.0), (5.0, 0.0, 0.0)),
          "c": ((3, 3, 3), (0.0, 0.008, 0.0), (0.0, 8.0, 0.0)),
          "d": ((2, 2, 2), (0.0, -0.010, 0.0), (0.0, -10.0, 0.0)),
          "e": ((5, 2, 2), (0.0, 0.0, 0.008), (0.0, 0.0, 12.0))}
FIGS = ["fragment_mass_distribution.png", "fragment_velocity.png", "fragment_count.png"]
EXACT = 1e-12  # relative: sums of a few dozen equal point masses, recomputed in another order


def deck(names, interval):
    lines = ["simulation: {solver: peridynamics, dimension: 3d, end_time: 2.0e-6}",
             f"peridynamics: {{fragment_interval: {interval}}}",
             "grid: {lower: [-0.02, -0.02, -0.02], upper: [0.02, 0.02, 0.02], cell_size: 1.0e-3}",
             "materials:",
             "  glass: {model: linear_elastic, density: 2200, youngs_modulus: 72e9, poisson_ratio: 0.25}",
             "bodies:"]
    for name in names:
        n, lo, v = BODIES[name]
        up = [lo[k] + n[k] * H for k in range(3)]
        lines.append(f"  - {{name: {name}, material: glass, velocity: {list(v)}, "
                     f"shape: {{type: box, lower: {list(lo)}, upper: {up}}}}}")
    return "\n".join(lines) + "\n"


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout + p.stderr


def close(a, b, what, rel=EXACT):
    if a is None or not math.isclose(a, b, rel_tol=rel, abs_tol=0.0):
        fail(f"{what}: {a} != {b} (relative tolerance {rel})")


def run_deck(ballista, folder, names, interval, extra=()):
    os.makedirs(folder)
    path = os.path.join(folder, "deck.yaml")
    with open(path, "w") as f:
        f.write(deck(names, interval))
    out = os.path.join(folder, "out")
    os.makedirs(out)
    # Figures of an earlier run, listed in its manifest as that run would have: the run must
    # clear them (io/run_folder.hpp), so that a figure it does not draw is not a stale one.
    with open(os.path.join(out, ".ballista-files"), "w") as f:
        f.write("# ballista run of an earlier process\n" + "".join(n + "\n" for n in FIGS))
    for name in FIGS:
        with open(os.path.join(out, name), "wb") as f:
            f.write(b"stale")
    rc, log = run([ballista, "run", path, "-o", out, "-q", "--threads", "1", *extra])
    if rc != 0:
        fail(f"ballista run {path}: exit {rc}: {log}")
    with open(os.path.join(out, "summary.json")) as f:
        return out, json.load(f), log


def last_snapshot(out):
    d = np.genfromtxt(os.path.join(out, "fragments.csv"), delimiter=",", names=True)
    return d[d["time"] == d["time"].max()], np.unique(d["time"])


def numpy_mott(m):
    """Independent fit: MLE of the exponential law of sqrt(m); R^2 of the Mott-plot line."""
    theta = np.mean(np.sqrt(m))
    ms = np.sort(m)[::-1]
    last = np.append(ms[1:] != ms[:-1], True)
    x, y = np.sqrt(ms[last]), np.log(np.nonzero(last)[0] + 1.0)
    return float(len(m)), float(theta ** 2), float(np.corrcoef(x, y)[0, 1] ** 2)


def check_five(ballista, folder):
    out, s, log = run_deck(ballista, folder, list(BODIES), 1.0e-6)
    fr = s.get("fragments")
    if not isinstance(fr, dict):
        fail(f"summary.json has no 'fragments': {s.keys()}")
    masses = np.array([np.prod(b[0]) * POINT_MASS for b in BODIES.values()])
    if fr["count"] != len(BODIES):
        fail(f"fragments.count = {fr['count']}, expected {len(BODIES)}")
    close(fr["largest_mass"], masses.max(), "largest_mass")
    close(fr["total_mass"], masses.sum(), "total_mass")
    close(fr["mean_mass"], masses.mean(), "mean_mass")
    close(fr["mass_weighted_mean_mass"], np.sum(masses**2) / masses.sum(), "mass_weighted_mean_mass")
    close(fr["time"], 2.0e-6, "snapshot time")
    n0, mu, r2 = numpy_mott(masses)
    close(fr["mott_N0"], n0, "mott_N0")
    close(fr["mott_mu"], mu, "mott_mu")
    close(fr["mott_r2"], r2, "mott_r2")
    snap, times = last_snapshot(out)
    order = np.argsort(-masses, kind="stable")
    if not np.array_equal(snap["points"], [np.prod(list(BODIES.values())[k][0]) for k in order]):
        fail(f"fragments.csv points {snap['points']} are not the bodies' point counts by mass")
    speeds = np.array([np.linalg.norm(b[2]) for b in BODIES.values()])[order]
    for k in range(len(speeds)):  # free flight: no bond between bodies, none stretched inside one
        close(snap["speed"][k], speeds[k], f"speed of fragment {k}")
    if len(times) != 2:
        fail(f"expected two snapshots (fragment_interval 1 us, end 2 us), got times {times}")
    for name in FIGS:
        check_png(os.path.join(out, name))
    if "no fragment figures" in log:
        fail(f"the run warned about the figures: {log}")


def check_two(ballista, tools, folder):
    out, s, _ = run_deck(ballista, folder, ["a", "d"], 0.0, ["--no-plots"])
    if any(f.endswith(".png") for f in os.listdir(out)):
        fail(f"--no-plots: PNG written in {out}")
    fr = s["fragments"]
    if fr["count"] != 2 or any(k in fr for k in ("mott_N0", "mott_mu", "mott_r2")) or "mott_reason" not in fr:
        fail(f"two fragments: expected count 2, no mott_* and a mott_reason: {fr}")
    if "at least 3" not in fr.get("mott_reason", ""):
        fail(f"two fragments: mott_reason {fr.get('mott_reason')!r}")
    close(fr["largest_mass"], 64 * POINT_MASS, "largest_mass (two)")
    rc, err = run([sys.executable, os.path.join(tools, "plot_fragments.py"), out])
    if rc != 0:
        fail(f"plot_fragments.py on two fragments: exit {rc}: {err}")
    check_png(os.path.join(out, "fragment_mass_distribution.png"))
    check_png(os.path.join(out, "fragment_velocity.png"))
    if os.path.exists(os.path.join(out, "fragment_count.png")) or "fragment_count.png skipped" not in err:
        fail(f"one snapshot: fragment_count.png must be skipped with a note: {err!r}")
    if "no Mott fit" not in err:
        fail(f"two fragments: no note about the missing Mott fit: {err!r}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ballista", required=True)
    ap.add_argument("--tools", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    check_five(a.ballista, os.path.join(a.out, "five"))
    check_two(a.ballista, a.tools, os.path.join(a.out, "two"))
    empty = os.path.join(a.out, "empty")
    os.makedirs(empty)
    rc, err = run([sys.executable, os.path.join(a.tools, "plot_fragments.py"), empty])
    if rc != 2 or "fragments.csv" not in err:
        fail(f"no fragments.csv: exit {rc} (expected 2), {err!r}")
    print("fragment plots: all checks passed")


if __name__ == "__main__":
    main()
