#!/usr/bin/python3
"""Fragment figures of one `ballista run` whose solver writes fragments.csv (peridynamics).

Usage: plot_fragments.py OUT_DIR [--time T]

Reads OUT_DIR/fragments.csv (columns time, fragment, points, mass, x, y, z, vx, vy, vz, speed,
kinetic_energy; SI; one block of rows per snapshot time) and writes into OUT_DIR:
  fragment_mass_distribution.png  cumulative number N(>=m) of fragments against mass m (log-linear
                                  axes) and on Mott axes (against sqrt(m), where the Mott law is a
                                  straight line), with the Mott fit N0 exp(-sqrt(m/mu)); N0 and mu
                                  in the legend (maximum likelihood, as src/analysis/mott_fit.hpp:
                                  sqrt(mu) = mean sqrt(m_i), N0 = number of fragments; Mott, Proc.
                                  R. Soc. A 189 (1947) 300; Grady & Kipp, J. Appl. Phys. 58 (1985)
                                  1210). Fewer than 3 fragments: the data without a fit.
  fragment_velocity.png           histogram of fragment speeds, by count and mass-weighted
  fragment_count.png              number of fragments and largest fragment's mass fraction against
                                  time (only when fragments.csv has several snapshots)
The last snapshot is used unless --time T picks the snapshot nearest to T (s). A figure without
data is skipped with a one-line note on stderr. Exit status 0 on success, 2 if OUT_DIR has no
fragments.csv or it lacks a needed column. Needs numpy and matplotlib (BALLISTA_PYTHON).
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend first)
import numpy as np  # noqa: E402

MOTT_MIN_FRAGMENTS = 3  # as kMottMinFragments in src/analysis/mott_fit.hpp
NEEDED = ("time", "mass", "speed")


def note(msg):
    print("plot_fragments: " + msg, file=sys.stderr)


def read_csv(path):
    """Columns of a CSV file with a header as float arrays (non-numbers -> nan); None if absent."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r]
    if not rows:
        return {}
    header = [h.strip() for h in rows[0]]
    cols = {h: [] for h in header}
    for r in rows[1:]:
        for i, h in enumerate(header):
            try:
                cols[h].append(float(r[i]) if i < len(r) else math.nan)
            except ValueError:
                cols[h].append(math.nan)
    return {h: np.asarray(v, dtype=float) for h, v in cols.items()}


def mott_fit(masses):
    """(N0, mu) by maximum likelihood (sqrt(m) ~ Exp with mean sqrt(mu)), None below 3 fragments."""
    m = np.asarray(masses, dtype=float)
    if m.size < MOTT_MIN_FRAGMENTS or not np.all(np.isfinite(m) & (m > 0)):
        return None
    theta = float(np.mean(np.sqrt(m)))
    return float(m.size), theta * theta


def cumulative(masses):
    """Distinct masses (descending) and N(>=m) at each: ties share the count including all of them."""
    m = np.sort(np.asarray(masses, dtype=float))[::-1]
    last = np.append(m[1:] != m[:-1], True)  # last member of each run of equal masses
    return m[last], np.nonzero(last)[0] + 1.0


def plot_mass(out_dir, m, t):
    mm, n = cumulative(m)
    fit = mott_fit(m)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    for a, x in ((ax, mm), (bx, np.sqrt(mm))):
        a.semilogy(x, n, "o", ms=4, label=f"fragments ({m.size})")
    if fit is not None:
        n0, mu = fit
        mg = np.linspace(0.0, float(mm.max()) * 1.05, 300)
        label = f"Mott fit: $N_0$ = {n0:.0f}, $\\mu$ = {mu:.4g} kg"
        ax.semilogy(mg, n0 * np.exp(-np.sqrt(mg / mu)), "-", label=label)
        bx.semilogy(np.sqrt(mg), n0 * np.exp(-np.sqrt(mg / mu)), "-", label=label)
    else:
        note(f"{m.size} fragment(s): no Mott fit (needs {MOTT_MIN_FRAGMENTS})")
    for a in (ax, bx):
        a.set_ylim(0.5, 2.0 * n.max())  # N >= 1 for every data point; N0 = n.max()
        a.set_ylabel("cumulative number of fragments N(≥m)")
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=8)
    ax.set_xlabel("fragment mass m [kg]")
    bx.set_xlabel("sqrt(m) [kg$^{1/2}$] (Mott plot)")
    fig.suptitle(f"Fragment mass distribution at t = {t:.4g} s")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "fragment_mass_distribution.png"), dpi=120)
    plt.close(fig)


def plot_velocity(out_dir, m, v, t):
    ok = np.isfinite(v)
    m, v = m[ok], v[ok]
    if v.size == 0:
        note("no finite fragment speeds: fragment_velocity.png skipped")
        return
    nb = int(min(30, max(5, round(math.sqrt(v.size)))))
    edges = np.histogram_bin_edges(v, bins=nb)
    by_count, _ = np.histogram(v, bins=edges)
    by_mass, _ = np.histogram(v, bins=edges, weights=m)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.stairs(by_count / v.size, edges, label=f"by count ({v.size} fragments)", lw=1.8)
    ax.stairs(by_mass / m.sum(), edges, label=f"mass-weighted ({m.sum():.4g} kg)", lw=1.8, ls="--")
    ax.set_xlabel("fragment speed [m/s]")
    ax.set_ylabel("fraction per bin")
    ax.set_title(f"Fragment speeds at t = {t:.4g} s")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "fragment_velocity.png"), dpi=120)
    plt.close(fig)


def plot_count(out_dir, time, mass, times):
    counts = np.array([np.count_nonzero(time == s) for s in times])
    largest = np.array([mass[time == s].max() / mass[time == s].sum() for s in times])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(times, counts, "o-", label="fragments")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("number of fragments")
    ax.grid(True, alpha=0.3)
    bx = ax.twinx()
    bx.plot(times, largest, "s--", color="C1", label="largest fragment / total mass")
    bx.set_ylabel("largest fragment's mass fraction")
    bx.set_ylim(0.0, 1.05)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = bx.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="center right")
    ax.set_title("Fragment count over the snapshots")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "fragment_count.png"), dpi=120)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dir")
    ap.add_argument("--time", type=float, default=None, help="snapshot nearest to this time (s); default: the last")
    a = ap.parse_args(argv[1:])
    path = os.path.join(a.out_dir, "fragments.csv")
    cols = read_csv(path)
    if cols is None:
        note(f"{path} not found (is OUT_DIR the folder of a ballista run with fragments?)")
        return 2
    missing = [c for c in NEEDED if c not in cols]
    if missing:
        note(f"{path} has no column {', '.join(missing)}")
        return 2
    time, mass, speed = cols["time"], cols["mass"], cols["speed"]
    if time.size == 0:
        note("fragments.csv has no fragments: fragment figures skipped")
        return 0
    times = np.unique(time)
    t = times[-1] if a.time is None else times[np.argmin(np.abs(times - a.time))]
    sel = time == t
    plot_mass(a.out_dir, mass[sel], t)
    plot_velocity(a.out_dir, mass[sel], speed[sel], t)
    if times.size >= 2:
        plot_count(a.out_dir, time, mass, times)
    else:
        note("one snapshot: fragment_count.png skipped")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
