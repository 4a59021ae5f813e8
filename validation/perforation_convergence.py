#!/usr/bin/env python3
"""Grid study of the perforation demo: depth and hole diameters under refinement around the jet.

Runs examples/jet_casing_sandstone_mpm.yaml at several levels of a graded grid (grid.refine): at
level h the cells are h in a radial band around the line of flight (0 <= r < --band) and in an
axial band along the jet's path (--path), graded to the deck's far-field cell_size outside;
levels halve h (ratio 2). For each level it records what a gun designer reads, the depth of
penetration into the rock, the casing's entrance-hole diameter, the cement's and the rock
tunnel's entrance diameter, with the run's cost. From the three finest levels: the observed order
p = log(|f1 - f2| / |f2 - f3|) / log 2, the Richardson estimate f3 + (f3 - f2) / (2^p - 1) and the
finest level's distance from it (Roache, "Verification and Validation in Computational Science and
Engineering", 1998, ch. 5; the grid convergence index uses the same extrapolation).

Writes DIR/convergence.json, DIR/convergence.md (the table for docs/validation.md),
DIR/convergence.png and DIR/final_states.png (each level's last output near the line of flight:
where the spent jet lies). Long (the finest level takes tens of minutes on 2 cores); not in make test.
A level that takes hours can be checkpointed and continued after an interruption:

  ... --set output.checkpoint_interval=5e-6            # first run, cut short
  ... --set output.checkpoint_interval=5e-6 --resume   # continues each level that has no completed summary
                                                       # (and keeps the completed ones)

  /usr/bin/python3 validation/perforation_convergence.py --ballista build/ballista --out out/perfconv

--deck runs another deck through the same levels, e.g. the demo's tip segment alone into the
confined rock (validation/jet_segment_sandstone.yaml, docs/validation.md):

  /usr/bin/python3 validation/perforation_convergence.py --deck validation/jet_segment_sandstone.yaml --out out/segment
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(REPO, "examples", "jet_casing_sandstone_mpm.yaml")
QUANTITIES = [
    ("depth", "depth into the rock", "mm"),
    ("casing_hole", "casing entrance hole diameter", "mm"),
    ("casing_mean_hole", "casing hole diameter averaged through its thickness", "mm"),
    ("cement_hole", "cement entrance hole diameter", "mm"),
    ("cement_mean_hole", "cement hole diameter averaged through its thickness", "mm"),
    ("tunnel_entrance", "rock tunnel entrance diameter", "mm"),
    ("cavity_depth", "cavity depth in the rock", "mm"),
    ("tunnel_depth", "depth the tunnel is as wide as the jet's tip", "mm"),
    ("tunnel_volume", "rock tunnel volume", "cm³"),
]


def level_sets(h, far, band, path):
    """--set overrides of one level: the bands at h (uniform when h is the far-field cell: the
    deck's own bands, if it has any, are cleared), one step for all and no patches (the deck's
    patches and step per region are a configuration the study checks, not one of its levels)."""
    plain = ["grid.patches=[]", "mpm.multirate=none"]
    if abs(h - far) < 1e-12 * far:
        return [f"grid.cell_size={far!r}", "grid.refine=[]"] + plain
    zones = (f"[{{axis: x, from: 0, to: {band!r}, cell_size: {h!r}}}, "
             f"{{axis: y, from: {path[0]!r}, to: {path[1]!r}, cell_size: {h!r}}}]")
    return [f"grid.cell_size={far!r}", f"grid.refine={zones}"] + plain


def level_done(out):
    """Whether the level in `out` has its answer. A run stopped by a signal or a failure writes its
    summary too (status "interrupted" or "failed"): only a completed run's summary is one."""
    summary = os.path.join(out, "summary.json")
    return os.path.exists(summary) and json.load(open(summary)).get("status") == "completed"


def run_level(a, h):
    out = os.path.join(a.out, f"h_{h * 1e3:g}mm")
    summary = os.path.join(out, "summary.json")
    done = level_done(out)
    # A resumed study keeps the levels it has completed: --resume alone must not run them again.
    if (a.reuse or a.resume) and done:
        return json.load(open(summary)), None
    checkpoints = os.path.join(out, "checkpoints")
    if a.resume and not done and os.path.isdir(checkpoints) and os.listdir(checkpoints):
        # A level cut short (a machine restart, a session's end) continues from its newest
        # checkpoint: the deck and the level's overrides are the checkpoint's (docs/restart.md).
        cmd = [a.ballista, "run", "--restart", out, "-q", "--no-plots", "--threads", str(a.threads)]
    else:
        cmd = [a.ballista, "run", a.deck, "-o", out, "-q", "--no-plots", "--threads", str(a.threads), "--overwrite"]
        for s in level_sets(h, a.far, a.band, a.path) + a.set:
            cmd += ["--set", s]
    print("running", " ".join(cmd), flush=True)
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        print(p.stdout[-3000:])
        raise SystemExit(f"level h = {h} failed (exit {p.returncode})")
    return json.load(open(summary)), wall


def first_main_step(out):
    """The first stable step of the main stage, from history.csv (the smallest step is judged
    against it: within 10x at every level)."""
    import csv
    rows = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    last = max(float(r.get("stage", 0) or 0) for r in rows)
    main = [float(r["dt"]) for r in rows if float(r.get("stage", 0) or 0) == last and float(r["dt"]) > 0]
    return main[0] if main else None


def segment_depths(out):
    """For each jet segment, the depth into the rock when it has slowed to half its speed (its
    kinetic energy, history.csv segment_kinetic_energy_k, first below a quarter of its peak in the
    main stage), m; None for a segment still faster at the end. What each segment adds to the
    depth is how the train's depth is built (docs/validation.md)."""
    import csv
    rows = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    last = max(float(r.get("stage", 0) or 0) for r in rows)
    rows = [r for r in rows if float(r.get("stage", 0) or 0) == last]
    depths = []
    k = 0
    while rows and f"segment_kinetic_energy_{k}" in rows[0]:
        key = f"segment_kinetic_energy_{k}"
        energy = [float(r[key]) for r in rows]
        peak_at = max(range(len(energy)), key=energy.__getitem__)
        hit = next((i for i in range(peak_at, len(energy)) if energy[i] < 0.25 * energy[peak_at]), None)
        depths.append(None if hit is None else float(rows[hit]["penetration_depth"]))
        k += 1
    return depths


DEPTH_TIMES = (30e-6, 40e-6, 50e-6, 60e-6, 70e-6, 80e-6)


def depth_at_times(out, t0, times=DEPTH_TIMES):
    """The depth into the rock (history.csv penetration_depth) at these times after the main stage
    began (at t0, summary.json main_stage_start), m: where the levels part in time (the jet's
    arrival at the rock, or its rate in it)."""
    import csv
    rows = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    if not rows or t0 is None:
        return [None for _ in times]
    depths = []
    for t in times:
        # The nearest row, if within 0.2 us (0.2 mm of depth at the jet's ~1 km/s in the rock).
        near = min(rows, key=lambda r: abs(float(r["time"]) - t0 - t))
        ok = abs(float(near["time"]) - t0 - t) <= 0.2e-6
        depths.append(float(near["penetration_depth"]) if ok else None)
    return depths


def tunnel_entrance(pen, out):
    """The rock tunnel's entrance diameter, m: summary.json's, or for a run written before that key
    had its rule (where the wall begins below a crushed face), the same rule on channel.csv."""
    t = pen.get("tunnel", {})
    if "entrance_depth" in t:
        return t.get("entrance_diameter")
    import csv
    for row in csv.DictReader(open(os.path.join(out, "channel.csv"))):
        r = float(row["radius"])
        if math.isfinite(r):
            return 2.0 * r
    return None


def tunnel_volume(out):
    """The rock tunnel's volume, cm^3: channel.csv's wall radius r(z) as a body of revolution about
    the line of flight, the sum of pi r^2 dz over the bins with a wall. What the jet's energy buys
    in the rock: a crater's volume grows with the energy the impactor delivers (in sandstone,
    Dufresne et al., Meteorit. Planet. Sci. 48 (2013), doi:10.1111/maps.12024), so levels that
    deliver the same energy can agree on it while they part on the tunnel's shape, depth against
    width."""
    import csv
    rows = list(csv.DictReader(open(os.path.join(out, "channel.csv"))))
    if len(rows) < 2:
        return None
    z = [float(r["depth"]) for r in rows]
    dz = z[1] - z[0]
    radii = [float(r["radius"]) for r in rows]
    return 1e6 * sum(math.pi * r * r * dz for r in radii if math.isfinite(r))


def final_points(out, pen):
    """The last particle output of a level (the run's end): the penetrator's and the target's
    points as (depth below the struck face, radius, mass, segment, failed), or None without h5py
    or output. Depth is measured along the line of flight, positive into the target."""
    import glob
    try:
        import h5py
        import numpy as np
    except ImportError:
        return None
    files = sorted(glob.glob(os.path.join(out, "particles_*.h5")))
    if not files:
        return None
    import yaml
    bodies = yaml.safe_load(open(os.path.join(out, "resolved.yaml")))["bodies"]
    jet = next(b for b in bodies if b["name"] == pen["penetrator"]).get("jet", {})
    if (jet.get("axis"), jet.get("direction")) != ("y", -1):
        return None  # the depth below assumes a jet flying along -y, as every deck of this study
    with h5py.File(files[-1], "r") as f:
        names = json.loads(f.attrs["body_names"])
        body = f["body"][:]
        x = f["x"][:]
        # Each point's half-extent along the line of flight, as the probe's cavity depth takes it:
        # |F_yx| h_x + |F_yy| h_y (the domain is F times the box of half-sizes h).
        if "F" in f and "half_size" in f:
            F, half = f["F"][:], f["half_size"][:]
            reach = np.abs(F[:, 3]) * half[:, 0] + np.abs(F[:, 4]) * half[:, 1]
        else:
            reach = np.zeros(body.size)
        fields = {"depth": pen["surface"] - x[:, 1], "r": np.abs(x[:, 0]), "mass": f["mass"][:],
                  "segment": f["segment"][:], "failed": f["failed"][:], "reach": reach}
    points = {}
    for role in ("penetrator", "target"):
        mine = body == names.index(pen[role])
        points[role] = {key: values[mine] for key, values in fields.items()}
    segments = jet.get("segments") or []
    points["tip_radius"] = float(segments[0][0]) if segments else None
    return points


SPENT_WINDOW = 10.0e-3


def jet_at_bottom(points, cavity_depth):
    """The share of the penetrator's mass within SPENT_WINDOW (10 mm) of the cavity's bottom at the
    end of the run. Each segment's copper, once spent, either lines the tunnel's wall or stays in
    the next segment's path; a lining spread evenly over a train's ~150 mm would put about a tenth
    of the jet, plus the last segment's own copper, in the last 10 mm. At 1 mm cells the spent
    copper piles at the bottom instead (docs/validation.md, "Where the spent copper ends, and
    why a cell cannot hold it"): the lining is thinner than a cell."""
    if points is None or cavity_depth is None:
        return None
    p = points["penetrator"]
    total = p["mass"].sum()
    if not total > 0:
        return None
    near = abs(p["depth"] - cavity_depth) <= SPENT_WINDOW
    return float(p["mass"][near].sum() / total)


def tunnel_depth(points, radius):
    """The depth to which the rock tunnel is at least `radius` wide: the shallowest intact target
    point closer than `radius` to the line of flight, less its half-extent along it (as the
    probe's cavity depth; failed points are debris, not wall). The probe's own cavity depth takes
    one cell as its radius, so on a finer grid it follows a narrower hole: at 0.25 mm cells the
    train's last 8 mm are a hole 0.1-0.2 mm wide along the axis that a few of the tip segment's
    points drill after the jet is spent (docs/validation.md, "A hole narrower than the jet").
    Taken at the jet's tip radius, the same width at every level, the depth is one quantity
    across the levels of a study."""
    if points is None or radius is None:
        return None
    t = points["target"]
    wall = (t["failed"] == 0) & (t["depth"] >= 0.0) & (t["r"] < radius)
    if not wall.any():
        return None
    return float((t["depth"][wall] - t["reach"][wall]).min())


def plot_final_states(a, states):
    """DIR/final_states.png: each level's last output near the line of flight (states: (h, points of
    final_points) per level), the penetrator's points coloured by segment, the target's failed
    points orange and its intact points grey."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    states = [(h, p) for h, p in states if p is not None]
    if not states:
        return
    deepest = max(float(p["penetrator"]["depth"].max()) for _, p in states) * 1e3
    fig, axes = plt.subplots(len(states), 1, figsize=(14, 1.9 * len(states)), squeeze=False)
    for ax, (h, p) in zip(axes[:, 0], states):
        t, j = p["target"], p["penetrator"]
        for mask, colour in ((t["failed"] == 0, "0.75"), (t["failed"] != 0, "orange")):
            ax.scatter(1e3 * t["depth"][mask], 1e3 * t["r"][mask], s=0.3, c=colour, lw=0)
        ax.scatter(1e3 * j["depth"], 1e3 * j["r"], s=1.0, c=j["segment"] % 10, cmap="tab10", vmin=0, vmax=9, lw=0)
        ax.set_xlim(-5, deepest + 10)
        ax.set_ylim(0, 12)
        ax.set_aspect("equal")
        ax.set_ylabel("r (mm)")
        ax.set_title(f"{h * 1e3:g} mm cells around the jet, end of the run", fontsize=9)
    axes[-1, 0].set_xlabel("depth below the struck face (mm)")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "final_states.png"), dpi=110)


def extract(s, out, points):
    pen = s["penetration"]
    holes = pen.get("holes", {})
    mm = lambda v: None if v is None else 1e3 * v
    return {
        "depth": mm(pen.get("final_depth")),
        # The channel's bottom in the rock: the depth without a single jet point driven ahead of it.
        "cavity_depth": mm(pen.get("final_cavity_depth")),
        # The same at one width for every level, the jet's tip radius (tunnel_depth).
        "tunnel_depth": mm(tunnel_depth(points, None if points is None else points["tip_radius"])),
        "casing_hole": mm(holes.get("casing", {}).get("entrance_diameter")),
        "cement_hole": mm(holes.get("cement", {}).get("entrance_diameter")),
        # The entrance is one slice of the finest cell, thinner at each level; the mean through the
        # layer is the same quantity at every level (summary holes.<layer>.mean_diameter).
        "casing_mean_hole": mm(holes.get("casing", {}).get("mean_diameter")),
        "cement_mean_hole": mm(holes.get("cement", {}).get("mean_diameter")),
        "hole_profiles": {layer: per_mm(holes.get(layer, {})) for layer in ("casing", "cement")},
        "tunnel_entrance": mm(tunnel_entrance(pen, out)),
        "tunnel_volume": tunnel_volume(out),
        # What the jet has left behind the casing and behind the cement, against the hydrodynamic
        # erosion T sqrt(rho_layer / rho_jet) (thesis eq. 3.2 inverted; docs/penetration.md).
        # (null for a jet formed in the run: it has no segments to follow)
        "jet_behind": {layer: {k: (holes.get(layer, {}).get("jet_behind") or {}).get(k)
                               for k in ("time", "consumed_length", "remaining_length", "tip_velocity",
                                         "tip_initial_velocity", "hydrodynamic_consumed_length")}
                       for layer in ("casing", "cement")},
        "min_dt": s["statistics"].get("min_dt"),
        "first_main_dt": first_main_step(out),
        "cells_across_radius": pen.get("cells_across_radius"),
        # Where the cells along the flight grow coarser than the band's, if the tunnel reaches there
        # (the run's path_cells; None: the band covers the whole tunnel).
        "coarser_from_depth": mm((pen.get("path_cells") or {}).get("coarser_from_depth")),
        # When the run ended because the jet was spent (penetration.end_when_spent), µs after firing;
        # None: it ran to end_time.
        "spent_time": (lambda t: None if t is None else 1e6 * t)((pen.get("end_when_spent") or {}).get("time")),
        "segment_depths": [mm(d) for d in segment_depths(out)],
        "depth_at_times": [mm(d) for d in depth_at_times(out, s.get("main_stage_start"))],
        "particles": s["statistics"]["particles_seeded"],
        "steps": s["statistics"]["steps"],
        "wall_time": s["statistics"]["wall_time"],
        "residual_over_scale": s["energy"]["residual_over_scale"],
        # Particles whose F was remapped at mpm.distortion_limit (docs/deck.md); absent: none.
        "distortion_remaps": s.get("solver_results", {}).get("distortion_remaps", 0),
        "jet_at_bottom": jet_at_bottom(points, pen.get("final_cavity_depth")),
    }


def per_mm(hole):
    """A layer's hole diameters (summary holes.<layer>.diameters, one per slice of the finest cell)
    averaged over each millimetre of its thickness, struck face first, in mm: the same slices at
    every level. None where a millimetre has no wall; [] without the profile."""
    d, t = hole.get("diameters"), hole.get("thickness")
    if not d or not t:
        return []
    n = max(1, round(len(d) / (t * 1e3)))  # slices per millimetre
    out = []
    for k in range(0, len(d), n):
        walls = [v for v in d[k:k + n] if v is not None]
        out.append(1e3 * sum(walls) / len(walls) if walls else None)
    return out


def oscillation(f1, f2, f3):
    """Half the range of three levels over the finest, when they oscillate (the differences change
    sign): oscillatory convergence has no order, and its uncertainty is half the range (Stern,
    Wilson, Coleman & Paterson, J. Fluids Eng. 123 (2001) 793). None otherwise."""
    if None in (f1, f2, f3) or not f3 or (f1 - f2) * (f2 - f3) >= 0:
        return None
    return 0.5 * (max(f1, f2, f3) - min(f1, f2, f3)) / abs(f3)


def richardson(f1, f2, f3, ratio=2.0):
    """Observed order and extrapolated value from three levels, coarse to fine."""
    if None in (f1, f2, f3):
        return None, None
    d12, d23 = f1 - f2, f2 - f3
    tiny = 1e-9 * max(abs(f1), abs(f2), abs(f3))  # the hole diameters are read in bins: equal to round-off
    if abs(d23) <= tiny or abs(d12) <= tiny or (d12 > 0) != (d23 > 0):
        return None, None  # not monotone: no order
    p = math.log(abs(d12) / abs(d23)) / math.log(ratio)
    if p <= 0:
        return p, None  # the differences do not shrink: there is no limit to extrapolate to
    return p, f3 - d23 / (ratio ** p - 1.0)  # f3 + (f3 - f2) / (r^p - 1): beyond the finest, away from the coarser


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ballista", default=os.path.join(REPO, "build", "ballista"))
    ap.add_argument("--deck", default=DECK, help="the deck run at every level (default: the demo)")
    ap.add_argument("--out", default=os.path.join(REPO, "out", "perforation_convergence"))
    ap.add_argument("--levels", type=float, nargs="+", default=[1.0e-3, 0.5e-3, 0.25e-3],
                    help="cell sizes in the bands, m, coarse to fine (ratio 2)")
    ap.add_argument("--far", type=float, default=1.0e-3, help="far-field cell size, m (the deck's)")
    ap.add_argument("--band", type=float, default=9.0e-3, help="radius of the refined band around the line of flight, m")
    ap.add_argument("--path", type=float, nargs=2, default=[-60.0e-3, 135.0e-3],
                    help="axial extent of the refined band, m (the jet's path through casing, cement and the rock to "
                         "160 mm deep; a level whose tunnel runs on beyond it says so)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--set", action="append", default=[], help="further --set overrides for every level")
    ap.add_argument("--reuse", action="store_true", help="reuse the summary of a level already run into --out")
    ap.add_argument("--resume", action="store_true",
                    help="continue a level that has checkpoints but no summary from its newest checkpoint "
                         "(run the levels with --set output.checkpoint_interval=...); its wall time is then "
                         "the last part's only. Completed levels are kept, as with --reuse")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows, states = [], []
    for h in a.levels:
        s, wall = run_level(a, h)
        out = os.path.join(a.out, f"h_{h * 1e3:g}mm")
        points = final_points(out, s["penetration"])
        r = extract(s, out, points)
        r["h"] = h
        print(json.dumps(r), flush=True)
        rows.append(r)
        states.append((h, points))
    plot_final_states(a, states)
    result = {"levels": rows, "band": a.band, "path": a.path, "far": a.far, "estimates": {}}
    if len(rows) >= 3:
        for key, what, unit in QUANTITIES:
            f = [r[key] for r in rows[-3:]]
            p, fr = richardson(*f)
            est = {"observed_order": p, "richardson": fr}
            swing = oscillation(*f)
            if fr:
                est["finest_relative_gap"] = abs(f[2] - fr) / abs(fr)
            elif swing is not None:
                est["oscillation"] = swing
            result["estimates"][key] = est
    json.dump(result, open(os.path.join(a.out, "convergence.json"), "w"), indent=2)
    lines = ["| band cell (mm) | cells across the tip radius | particles | steps | wall time (s) | depth (mm) | "
             "casing hole (mm) | casing hole, mean (mm) | cement hole (mm) | cement hole, mean (mm) | "
             "rock tunnel entrance (mm) | cavity depth (mm) | "
             "tunnel depth at the jet's tip radius (mm) | tunnel volume (cm³) | jet spent at (µs) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    fmt = lambda v: "—" if v is None else f"{v:.3g}"
    for r in rows:
        lines.append(f"| {r['h'] * 1e3:g} | {fmt(r['cells_across_radius'])} | {r['particles']} | {r['steps']} | "
                     f"{r['wall_time']:.0f} | {fmt(r['depth'])} | {fmt(r['casing_hole'])} | "
                     f"{fmt(r.get('casing_mean_hole'))} | {fmt(r['cement_hole'])} | {fmt(r.get('cement_mean_hole'))} | "
                     f"{fmt(r['tunnel_entrance'])} | {fmt(r['cavity_depth'])} | {fmt(r['tunnel_depth'])} | "
                     f"{fmt(r['tunnel_volume'])} | "
                     f"{fmt(r.get('spent_time'))} |")
    if result["estimates"]:
        for name, key in (("observed order", "observed_order"), ("Richardson estimate", "richardson"),
                          ("finest vs Richardson", "finest_relative_gap")):
            cells = []
            for q, _, _ in QUANTITIES:
                e = result["estimates"][q]
                v = e.get(key)
                if v is None and key == "finest_relative_gap" and e.get("oscillation") is not None:
                    cells.append(f"oscillates ±{100 * e['oscillation']:.1f} %")
                    continue
                cells.append("—" if v is None else (f"{100 * v:.1f} %" if key == "finest_relative_gap" else f"{v:.3g}"))
            lines.append(f"| {name} | | | | | " + " | ".join(cells) + " |")
    for r in rows:
        if r.get("coarser_from_depth") is not None:
            lines.append(f"\nNOT CONVERGED at {r['h'] * 1e3:g} mm: the refined band along the flight ends "
                         f"{r['coarser_from_depth']:.1f} mm deep and the tunnel runs on in coarser cells "
                         "(a deeper --path).")
    # Where the jet goes (the casing's cost explained) and the axis (smallest step vs the first).
    lines += ["", "| band cell (mm) | jet consumed by the casing (mm; hydrodynamic) | tip speed behind the casing "
              "(m/s; initial) | consumed by casing + cement (mm; hydrodynamic) | tip speed behind the cement (m/s; "
              "initial) | smallest step / first main step | F remaps | jet within 10 mm of the cavity's bottom at the end |",
              "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = []
        for layer in ("casing", "cement"):
            j = r["jet_behind"][layer]
            mm = lambda v: "—" if v is None else f"{1e3 * v:.3g}"
            speed = lambda v: "—" if v is None else f"{v:.0f}"
            cells += [f"{mm(j['consumed_length'])} ({mm(j['hydrodynamic_consumed_length'])})",
                      f"{speed(j['tip_velocity'])} ({speed(j['tip_initial_velocity'])})"]
        ratio = (f"1/{r['first_main_dt'] / r['min_dt']:.1f}" if r["min_dt"] and r["first_main_dt"] else "—")
        share = r.get("jet_at_bottom")
        lines.append(f"| {r['h'] * 1e3:g} | " + " | ".join(cells) + f" | {ratio} | {r.get('distortion_remaps', 0)} | "
                     + ("—" if share is None else f"{100 * share:.0f} %") + " |")
    # The holes' shape through the plates, in the same millimetre slices at every level.
    for layer in ("casing", "cement"):
        if any(r.get("hole_profiles", {}).get(layer) for r in rows):
            lines += ["", f"| band cell (mm) | {layer} hole diameter in each millimetre of its thickness, struck face "
                          "first (mm) |", "|---|---|"]
            for r in rows:
                lines.append(f"| {r['h'] * 1e3:g} | " + ", ".join(fmt(d) for d in r["hole_profiles"].get(layer, []))
                             + " |")
    # How the depth is built: the depth when each segment has slowed to half its speed.
    if any(r["segment_depths"] for r in rows):
        lines += ["", "| band cell (mm) | depth when each segment has slowed to half its speed, tip first (mm) |",
                  "|---|---|"]
        for r in rows:
            lines.append(f"| {r['h'] * 1e3:g} | " + ", ".join(fmt(d) for d in r["segment_depths"]) + " |")
    # When the levels part: the depth at equal times after the main stage began.
    lines += ["", "| band cell (mm) | " + " | ".join(f"depth at {t * 1e6:g} µs (mm)" for t in DEPTH_TIMES) + " |",
              "|---|" + "---|" * len(DEPTH_TIMES)]
    for r in rows:
        lines.append(f"| {r['h'] * 1e3:g} | " + " | ".join(fmt(d) for d in r["depth_at_times"]) + " |")
    open(os.path.join(a.out, "convergence.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        ncol = 3
        nrow = -(-len(QUANTITIES) // ncol)
        fig, axes = plt.subplots(nrow, ncol, figsize=(4.5 * ncol, 3.4 * nrow), squeeze=False)
        hs = [r["h"] * 1e3 for r in rows]
        for ax in axes.flat[len(QUANTITIES):]:
            ax.set_visible(False)
        for ax, (key, what, unit) in zip(axes.flat, QUANTITIES):
            ax.plot(hs, [math.nan if r.get(key) is None else r[key] for r in rows], "o-", label="Ballista")
            fr = result["estimates"].get(key, {}).get("richardson")
            if fr:
                ax.axhline(fr, ls="--", color="gray", label="Richardson estimate")
            ax.set_xscale("log", base=2)
            ax.invert_xaxis()
            ax.set_xlabel("cell size around the jet (mm)")
            ax.set_ylabel(f"{what} ({unit})", fontsize=8)
            ax.legend(fontsize=8)
        fig.suptitle("Perforation demo under refinement around the jet")
        fig.tight_layout()
        fig.savefig(os.path.join(a.out, "convergence.png"), dpi=110)
    except ImportError as e:
        print("no figure:", e)
    return 0


if __name__ == "__main__":
    sys.exit(main())
