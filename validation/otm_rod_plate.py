"""A rod through a plate under OTM and MPM side by side, at several cell sizes.

Runs examples/rod_plate_otm.yaml (OTM, pinball contact) and its MPM twin validation/rod_plate_mpm.yaml
(the same rod, plate and materials; GIMP, USAVG, frictionless multi-field contact) at each cell size
and reads, at the end of each run (30 us, the rod through the plate and its speed steady):
  - the residual velocity: the rod's mass-weighted mean axial speed (every rod point: the rod has
    no failure model, so all of it is still rod);
  - the hole's diameter: twice the smallest radius of the intact plate points (failed == 0) that lie
    within the plate's original thickness (0 <= y <= 6 mm), i.e. the narrowest bore through what
    is left of the plate; failed points (debris, the eroded rim) are not wall.
Prints a table, the relative difference OTM - MPM per level, and each solver's observed order
(log2 of the ratio of successive differences) over the three finest levels.

  /usr/bin/python3 validation/otm_rod_plate.py --ballista build/ballista --out out/otm_rod_plate
  (--levels 1e-3 0.5e-3 0.25e-3 by default; --threads N; --solvers mpm for one solver's runs only)
"""
import json
import math
import os
import sys

import h5py

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from case_runs import run_once, study_arguments, summary  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECKS = {"otm": os.path.join(REPO, "examples", "rod_plate_otm.yaml"),
         "mpm": os.path.join(REPO, "validation", "rod_plate_mpm.yaml")}
PLATE, ROD = 0, 1               # body indices in both decks
PLATE_TOP = 6.0e-3              # m, the plate spans 0 <= y <= 6 mm
SPEED = 1500.0                  # m/s, the rod's impact speed


def measure(folder):
    """(residual velocity m/s, hole diameter m) from the last particle file; None if not completed."""
    s = summary(folder)
    if s is None or s["status"] != "completed":
        return None
    files = sorted(f for f in os.listdir(folder) if f.startswith("particles_") and f.endswith(".h5"))
    with h5py.File(os.path.join(folder, files[-1]), "r") as h:
        x, v, m, body, failed = h["x"][:], h["v"][:], h["mass"][:], h["body"][:], h["failed"][:]
    rod = body == ROD
    residual = -float((m[rod] * v[rod, 1]).sum() / m[rod].sum())
    wall = (body == PLATE) & (failed == 0) & (x[:, 1] >= 0.0) & (x[:, 1] <= PLATE_TOP)
    hole = 2.0 * float(x[wall, 0].min())
    return residual, hole


def order(f):
    """Observed order and Richardson estimate from three values at ratio 2 (None if not monotone)."""
    d1, d2 = f[1] - f[0], f[2] - f[1]
    if d1 == 0.0 or d2 == 0.0 or d1 * d2 < 0.0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log(abs(d1) / abs(d2), 2.0)
    return p, f[2] + d2 / (2.0 ** p - 1.0)


def main():
    ap = study_arguments(__doc__, os.path.join(REPO, "out", "otm_rod_plate"))
    ap.add_argument("--levels", type=float, nargs="+", default=[1.0e-3, 0.5e-3, 0.25e-3])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--figure", help="draw both solvers' rod and plate at the end of the finest level into this PNG")
    ap.add_argument("--result", help="also write the numbers as JSON to this file in --out (ballista validate)")
    ap.add_argument("--solvers", nargs="+", default=list(DECKS), choices=list(DECKS),
                    help="run only these (the table shows every level found)")
    a = ap.parse_args()
    rows = {}
    for h in a.levels:
        for solver, deck in DECKS.items():
            folder = os.path.join(a.out, f"{solver}_{h * 1e3:g}mm")
            if not a.table_only and solver in a.solvers:
                run_once(a.ballista, deck, folder, ["--set", f"grid.cell_size={h!r}", "--threads", str(a.threads)])
            rows[(solver, h)] = (measure(folder), summary(folder))
    print("| cell | solver | points | steps | wall | energy residual / scale | residual velocity | hole diameter |")
    print("|---|---|---|---|---|---|---|---|")
    for h in a.levels:
        for solver in DECKS:
            r, s = rows[(solver, h)]
            if r is None:
                print(f"| {h * 1e3:g} mm | {solver} | not completed | | | | | |")
                continue
            st = s["statistics"]
            print(f"| {h * 1e3:g} mm | {solver} | {st['particles']:,} | {st['steps']:,} | {st['wall_time']:.0f} s | "
                  f"{s['energy']['residual_over_scale']:.3f} | {r[0]:.0f} m/s ({r[0] / SPEED:.3f}) | {r[1] * 1e3:.2f} mm |")
    print()
    result = {"levels": [], "orders": {}}
    for h in a.levels:
        o, m = rows[("otm", h)][0], rows[("mpm", h)][0]
        level = {"cell": h, "otm": o and {"residual_velocity": o[0], "hole_diameter": o[1]},
                 "mpm": m and {"residual_velocity": m[0], "hole_diameter": m[1]}}
        if o and m:
            level["velocity_difference_pct"] = 100 * (o[0] / m[0] - 1)
            level["hole_difference_pct"] = 100 * (o[1] / m[1] - 1)
            result["finest"] = level
            print(f"{h * 1e3:g} mm: OTM against MPM: residual velocity {level['velocity_difference_pct']:+.1f} %, "
                  f"hole {level['hole_difference_pct']:+.1f} %")
        result["levels"].append(level)
    if len(a.levels) >= 3:
        for solver in DECKS:
            done = [h for h in a.levels if rows[(solver, h)][0]]
            vals = [rows[(solver, h)][0] for h in done[-3:]]
            if len(vals) == 3:
                for k, what in ((0, "residual velocity"), (1, "hole diameter")):
                    p, est = order([v[k] for v in vals])
                    result["orders"][f"{solver}_{'velocity' if k == 0 else 'hole'}"] = {"order": p, "richardson": est}
                    print(f"{solver} {what}: " + ("not monotone or not converging" if p is None else
                                                 f"observed order {p:.2f}, Richardson {est if k == 0 else est * 1e3:.4g}"))

    if a.result:
        json.dump(result, open(os.path.join(a.out, a.result), "w"), indent=2)
    if a.figure and "finest" in result:
        draw(a.out, result["finest"]["cell"], a.figure)


def draw(out, h, path):
    """The points of both runs at cell h at the end: plate blue (failed points grey), rod red."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(7, 6), sharey=True)
    for ax, solver in zip(axes, DECKS):
        folder = os.path.join(out, f"{solver}_{h * 1e3:g}mm")
        files = sorted(f for f in os.listdir(folder) if f.startswith("particles_") and f.endswith(".h5"))
        with h5py.File(os.path.join(folder, files[-1]), "r") as f5:
            x, body, failed, t = f5["x"][:], f5["body"][:], f5["failed"][:], float(f5["time"][()])
        for sel, colour in (((body == PLATE) & (failed == 0), "tab:blue"), ((body == PLATE) & (failed != 0), "0.7"),
                            (body == ROD, "tab:red")):
            ax.scatter(1e3 * x[sel, 0], 1e3 * x[sel, 1], s=0.5, c=colour, linewidths=0)
        ax.set_aspect("equal")
        ax.set_xlim(0, 16)
        ax.set_ylim(-40, 10)
        ax.set_xlabel("r [mm]")
        ax.set_title(f"{solver.upper()}, {h * 1e3:g} mm, {1e6 * t:.0f} us")
    axes[0].set_ylabel("y [mm]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, path), dpi=110)


if __name__ == "__main__":
    main()
