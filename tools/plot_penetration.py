#!/usr/bin/python3
"""Penetration figures of one `ballista run` with a `penetration:` section (thesis seed 000 ch. 7.2).

Usage: plot_penetration.py OUT_DIR

Reads OUT_DIR/history.csv, penetration.csv, channel.csv and summary.json (key `penetration`) and
writes into OUT_DIR:
  penetration_depth.png   depth and cavity depth against time since firing (mm, us), the
                          steady-state linear fit dashed, U_h t dotted, analytic depths as
                          horizontal lines (thesis Fig. 7.4)
  penetration_rate.png    penetration rate against time, steady rate dashed, U_h (Fig. 7.5)
  penetrator_energy.png   penetrator kinetic energy, total and per segment (Figs. 7.6-7.7)
  channel_profile.png     hole radius through the layers and tunnel wall radius against depth (mm)
A figure whose data are missing is skipped with a one-line note on stderr. Exit status 0 on
success, 2 if OUT_DIR has no history.csv. Needs numpy and matplotlib (BALLISTA_PYTHON).
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend first)
import numpy as np  # noqa: E402

MM = 1e3  # m -> mm
US = 1e6  # s -> us
SEGMENT_LEGEND_MAX = 8  # up to this many segments get a legend; more are coloured by index + colourbar


def note(msg):
    print("plot_penetration: " + msg, file=sys.stderr)


def read_csv(path):
    """Columns of a CSV file with a header as float arrays (non-numbers -> nan); None if absent/empty."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        return None
    header = [h.strip() for h in rows[0]]
    cols = {h: [] for h in header}
    for r in rows[1:]:
        if not r:
            continue
        for i, h in enumerate(header):
            try:
                cols[h].append(float(r[i]) if i < len(r) else math.nan)
            except ValueError:
                cols[h].append(math.nan)
    return {h: np.asarray(v, dtype=float) for h, v in cols.items()}


def number(obj, key):
    """obj[key] as a finite float, else None (missing, null, not a number)."""
    if not isinstance(obj, dict):
        return None
    v = obj.get(key)
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    return float(v) if math.isfinite(v) else None


def read_summary(out_dir):
    path = os.path.join(out_dir, "summary.json")
    if not os.path.isfile(path):
        note("no summary.json: figures without the fit, U_h and analytic lines")
        return {}
    try:
        with open(path) as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        note(f"summary.json unreadable ({e}): figures without the fit, U_h and analytic lines")
        return {}
    p = s.get("penetration") if isinstance(s, dict) else None
    return p if isinstance(p, dict) else {}


def depth_series(hist, pen):
    """(t [s], depth [m], cavity depth [m] or None) since firing: penetration.csv, else history.csv."""
    if pen is not None and "time" in pen and "depth" in pen:
        t = pen["time"]
        return t, pen["depth"], pen.get("cavity_depth")
    if "penetration_time" in hist and "penetration_depth" in hist:
        t = hist["penetration_time"]
        after = t >= 0  # before firing (a preparation stage) the time is nan or negative
        if not np.any(after):
            return None  # stopped before the penetrator was fired
        cav = hist.get("cavity_depth")
        return t[after], hist["penetration_depth"][after], None if cav is None else cav[after]
    return None



def subject(p):
    """"'jet' into 'target' at 7000 m/s": what the run fired, from summary.json."""
    pen, tgt, v = p.get("penetrator"), p.get("target"), number(p, "impact_velocity")
    if not pen or not tgt:
        return ""
    return f"'{pen}' into '{tgt}'" + ("" if v is None else f" at {v:.0f} m/s")


def convergence_note(p):
    """The run's own statement that it is under-resolved (summary `resolved`), with its cause: the
    penetrator's cells across its radius, or a tunnel running on beyond the refined band."""
    if p.get("resolved") is not False:
        return ""
    coarser = number(p.get("path_cells") or {}, "coarser_from_depth")
    if coarser is not None:
        return (f"NOT CONVERGED: the refined band along the flight ends {coarser * 1e3:.1f} mm deep; "
                "the tunnel's end lies in coarser cells")
    cells = number(p, "cells_across_radius")
    if cells is not None:
        return (f"NOT CONVERGED: the penetrator is {cells:.2g} cells across its radius "
                "(depth and rate converge from about 4; docs/validation.md)")
    if p.get("formed_jet"):
        return "CONVERGENCE NOT KNOWN: the jet formed in the run; a grid study of the deck would say how far"
    return ""


def save(fig, ax, out_dir, name, title, p, source):
    """Grid, legend (if anything is labelled), a title saying what is shown and for which run, and
    a caption with where the figure's form comes from and, for an under-resolved run, that it is
    not converged; writes OUT_DIR/name and closes the figure."""
    ax.grid(alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="best")
    what = subject(p)
    ax.set_title(f"{title}: {what}" if what else title, fontsize=10)
    caption = [c for c in (convergence_note(p), source) if c]
    fig.tight_layout(rect=(0, 0.03 * len(caption), 1, 1))
    for k, c in enumerate(caption):
        fig.text(0.01, 0.01 + 0.03 * (len(caption) - 1 - k), c, fontsize=7,
                 color="tab:red" if c.startswith("NOT CONVERGED") else "0.3")
    fig.savefig(os.path.join(out_dir, name), dpi=120)
    plt.close(fig)

def plot_depth(out_dir, series, p):
    if series is None:
        note("penetration_depth.png skipped: no depth data (penetration.csv or history.csv penetration_depth "
             "after the penetrator was fired)")
        return
    t, d, cav = series
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.plot(t * US, d * MM, "k-", lw=1.6, label="penetration depth")
    if cav is not None and np.any(np.isfinite(cav)):
        ax.plot(t * US, cav * MM, "-", color="tab:blue", lw=1.2, label="cavity depth")
    rate, fit = number(p, "steady_rate"), p.get("steady_fit")
    intercept = number(fit, "intercept")
    if rate is not None and intercept is not None:
        t0, t1 = number(fit, "t_begin"), number(fit, "t_end")
        t0 = float(np.nanmin(t)) if t0 is None else t0
        t1 = float(np.nanmax(t)) if t1 is None else t1
        tt = np.linspace(t0, t1, 50)
        r2 = number(fit, "r2")
        lab = f"steady fit, U = {rate:.0f} m/s" + ("" if r2 is None else f" (r² = {r2:.4f})")
        ax.plot(tt * US, (intercept + rate * tt) * MM, "--", color="tab:red", lw=1.2, label=lab)
    uh = number(p, "hydrodynamic_rate")
    if uh is not None:
        # From the moment the penetrator reaches the target (summary arrival_time, else t = 0).
        ta = number(p, "arrival_time")
        ta = 0.0 if ta is None else ta
        tt = np.linspace(ta, float(np.nanmax(t)), 50)
        ax.plot(tt * US, uh * (tt - ta) * MM, ":", color="tab:green", lw=1.4, label=f"hydrodynamic U_h (t - t_arrival), U_h = {uh:.0f} m/s")
    lines = []
    for a in p.get("analytic") or []:
        if number(a, "depth") is not None:
            lines.append((str(a.get("name", "analytic")), number(a, "depth")))
    hd = number(p, "hydrodynamic_depth")
    if hd is not None and not any(abs(d - hd) <= 1e-9 * abs(hd) for _, d in lines):  # not already in `analytic`
        lines.insert(0, ("hydrodynamic depth L√(ρp/ρt)", hd))
    colours = plt.cm.tab10(np.linspace(0.3, 1.0, max(len(lines), 1)))
    for (name, depth), c in zip(lines, colours):
        ax.axhline(depth * MM, color=c, lw=0.9, ls="-.", label=f"{name}: {depth * MM:.1f} mm")
    ax.set_xlabel("time since firing [µs]")
    ax.set_ylabel("depth below target surface [mm]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    save(fig, ax, out_dir, "penetration_depth.png", "Depth", p,
         "Depth and cavity depth against time since firing; form of thesis seed 000 Fig. 7.4")


def plot_rate(out_dir, pen, p):
    if pen is None or "time" not in pen or "rate" not in pen:
        note("penetration_rate.png skipped: no penetration.csv with time and rate")
        return
    t = pen["time"]
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.plot(t * US, pen["rate"], "k-", lw=1.4, label="penetration rate dP/dt")
    if "cavity_rate" in pen and np.any(np.isfinite(pen["cavity_rate"])):
        ax.plot(t * US, pen["cavity_rate"], "-", color="tab:blue", lw=1.0, label="cavity rate")
    rate = number(p, "steady_rate")
    if rate is not None:
        fit = p.get("steady_fit")
        t0, t1 = number(fit, "t_begin"), number(fit, "t_end")
        if t0 is not None and t1 is not None:
            ax.plot([t0 * US, t1 * US], [rate, rate], "--", color="tab:red", lw=1.4, label=f"steady U = {rate:.0f} m/s")
        else:
            ax.axhline(rate, ls="--", color="tab:red", lw=1.2, label=f"steady U = {rate:.0f} m/s")
    uh = number(p, "hydrodynamic_rate")
    if uh is not None:
        ax.axhline(uh, ls=":", color="tab:green", lw=1.4, label=f"hydrodynamic U_h = {uh:.0f} m/s")
    ax.set_xlabel("time since firing [µs]")
    ax.set_ylabel("penetration rate [m/s]")
    ax.set_xlim(left=0)
    save(fig, ax, out_dir, "penetration_rate.png", "Penetration rate", p,
         "Rate dP/dt by local polynomial differentiation; form of thesis seed 000 Fig. 7.5")


def segment_columns(hist):
    """history.csv segment_kinetic_energy_<k> columns ordered by k."""
    segs = []
    for h in hist:
        if h.startswith("segment_kinetic_energy_"):
            try:
                segs.append((int(h.rsplit("_", 1)[1]), h))
            except ValueError:
                pass
    return [h for _, h in sorted(segs)]


def plot_energy(out_dir, hist, p):
    segs = segment_columns(hist)
    if "penetrator_kinetic_energy" not in hist and not segs:
        note("penetrator_energy.png skipped: no penetrator_kinetic_energy / segment_kinetic_energy_* in history.csv")
        return
    if "penetration_time" in hist:
        t, xlabel = hist["penetration_time"] * US, "time since firing [µs]"
    elif "time" in hist:
        t, xlabel = hist["time"] * US, "time [µs]"
    else:
        note("penetrator_energy.png skipped: history.csv has no time column")
        return
    fig, ax = plt.subplots(figsize=(6.8, 4.6))
    if segs:
        cmap = plt.cm.viridis
        n = len(segs)
        for k, h in enumerate(segs):
            c = cmap(k / max(n - 1, 1))
            ax.plot(t, hist[h], "-", color=c, lw=1.0, label=f"segment {k}" if n <= SEGMENT_LEGEND_MAX else None)
        if n > SEGMENT_LEGEND_MAX:
            sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0, n - 1))
            fig.colorbar(sm, ax=ax, label="segment index")
    if "penetrator_kinetic_energy" in hist:
        ax.plot(t, hist["penetrator_kinetic_energy"], "k-", lw=1.8, label="penetrator total")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("kinetic energy [J]")
    save(fig, ax, out_dir, "penetrator_energy.png", "Penetrator kinetic energy", p,
         "Kinetic energy of the penetrator and of each segment; form of thesis seed 000 Figs. 7.6-7.7")


def plot_channel(out_dir, ch, p):
    if ch is None or "depth" not in ch or "radius" not in ch:
        note("channel_profile.png skipped: no channel.csv with depth and radius")
        return
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.plot(ch["depth"] * MM, ch["radius"] * MM, "k-", lw=1.4, label="tunnel wall (dense material)")
    if "innermost_radius" in ch:
        ax.plot(ch["depth"] * MM, ch["innermost_radius"] * MM, "-", color="0.6", lw=0.8,
                label="innermost intact material")
    # The holes through the layers before the target (casing, cement) at their depths (< 0).
    holes = p.get("holes") if isinstance(p.get("holes"), dict) else {}
    for k, (name, h) in enumerate(holes.items()):
        top, thick, d = h.get("face_depth"), h.get("thickness"), h.get("entrance_diameter")
        if top is None or thick is None or d is None:
            continue
        c = plt.cm.tab10(k + 1)
        ax.plot([top * MM, (top + thick) * MM], [0.5 * d * MM] * 2, "-", color=c, lw=2.2,
                label=f"{name}: entrance hole {d * MM:.2f} mm dia.")
    # The rock tunnel's entrance: where its wall begins (below a crushed or blown-off face).
    tunnel = p.get("tunnel") if isinstance(p.get("tunnel"), dict) else {}
    d, at = tunnel.get("entrance_diameter"), tunnel.get("entrance_depth")
    if d is not None and at is not None:
        ax.plot([at * MM], [0.5 * d * MM], "D", color="k", ms=6,
                label=f"tunnel entrance {d * MM:.2f} mm dia. at {at * MM:.2f} mm")
    rmax = number(p, "max_channel_radius")
    if rmax is not None:
        ax.axhline(rmax * MM, ls="--", color="tab:red", lw=1.0, label=f"largest tunnel radius {rmax * MM:.2f} mm")
    ax.set_xlabel("depth below the target's face [mm]")
    ax.set_ylabel("radius [mm]")
    ax.set_ylim(bottom=0)
    save(fig, ax, out_dir, "channel_profile.png", "Hole and tunnel radius", p,
         "Radius of the holes through the plates and of the tunnel wall against depth (docs/penetration.md)")


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 1
    out_dir = argv[1]
    hist = read_csv(os.path.join(out_dir, "history.csv"))
    if hist is None:
        print(f"plot_penetration: {os.path.join(out_dir, 'history.csv')} not found or empty "
              "(is OUT_DIR the folder of a ballista run?)", file=sys.stderr)
        return 2
    pen = read_csv(os.path.join(out_dir, "penetration.csv"))
    ch = read_csv(os.path.join(out_dir, "channel.csv"))
    p = read_summary(out_dir)
    plot_depth(out_dir, depth_series(hist, pen), p)
    plot_rate(out_dir, pen, p)
    plot_energy(out_dir, hist, p)
    plot_channel(out_dir, ch, p)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
