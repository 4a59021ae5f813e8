#!/usr/bin/python3
"""Figures of an impact-velocity sweep with penetration data (thesis seed 000 §5.2, Figs. 5.11-5.12).

Usage: plot_sweep_penetration.py SWEEP_DIR

Reads SWEEP_DIR/sweep_penetration.json (written by `ballista sweep`, src/run/sweep_penetration_fit.*)
and writes into SWEEP_DIR:
  penetration_u_vs_v.png     steady penetration rate U against impact velocity V, the fit
                             U = a + b V (a, b, r² in the legend) and the hydrodynamic U_h (Fig. 5.11)
  penetration_u_over_uh.png  U / U_h against V (Fig. 5.12)
Exit status 0 on success, 2 if the JSON is missing or has no runs. Needs numpy and matplotlib.
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend first)
import numpy as np  # noqa: E402

KM = 1e-3  # m/s -> km/s


def num(v):
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) else math.nan


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 1
    path = os.path.join(argv[1], "sweep_penetration.json")
    try:
        with open(path) as f:
            d = json.load(f)
    except (OSError, ValueError) as e:
        print(f"plot_sweep_penetration: cannot read {path}: {e}", file=sys.stderr)
        return 2
    runs = d.get("runs") or []
    if not runs:
        print(f"plot_sweep_penetration: {path} has no runs", file=sys.stderr)
        return 2
    order = sorted(range(len(runs)), key=lambda i: num(runs[i].get("V")))
    V = np.array([num(runs[i].get("V")) for i in order])
    U = np.array([num(runs[i].get("U")) for i in order])
    Uh = np.array([num(runs[i].get("U_h")) for i in order])
    a, b, r2 = num(d.get("a")), num(d.get("b")), num(d.get("r2"))

    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    ax.plot(V * KM, U * KM, "o", color="k", label="simulations")
    vv = np.linspace(0.0, np.nanmax(V) * 1.05, 100)
    if math.isfinite(a) and math.isfinite(b):
        ax.plot(vv * KM, (a + b * vv) * KM, "--", color="tab:red",
                label=f"U = a + bV: a = {a:.0f} m/s, b = {b:.3f}, r² = {r2:.4f}")
    if np.any(np.isfinite(Uh)):
        # U_h / V is fixed by the densities: a line through the origin when they are the same in every run.
        ratio = Uh / V
        if np.nanmax(ratio) - np.nanmin(ratio) <= 1e-12 * np.nanmax(np.abs(ratio)):
            ax.plot(vv * KM, np.nanmean(ratio) * vv * KM, ":", color="tab:green", lw=1.6,
                    label="hydrodynamic U_h = V / (1 + √(ρt/ρp))")
        else:
            ax.plot(V * KM, Uh * KM, ":s", color="tab:green", label="hydrodynamic U_h (per run)")
    ax.set_xlabel("impact velocity V [km/s]")
    ax.set_ylabel("penetration velocity U [km/s]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title("Penetration velocity against impact velocity (thesis Fig. 5.11)")
    fig.tight_layout()
    fig.savefig(os.path.join(argv[1], "penetration_u_vs_v.png"), dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    ok = np.isfinite(U / Uh)
    if np.any(ok):
        ax.plot(V[ok] * KM, (U / Uh)[ok], "o-", color="k", label="U / U_h")
    ax.axhline(1.0, ls=":", color="tab:green", label="hydrodynamic limit")
    ax.set_xlabel("impact velocity V [km/s]")
    ax.set_ylabel("U / U_h [-]")
    ax.set_xlim(left=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    ax.set_title("Normalised penetration velocity (thesis Fig. 5.12)")
    fig.tight_layout()
    fig.savefig(os.path.join(argv[1], "penetration_u_over_uh.png"), dpi=120)
    plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
