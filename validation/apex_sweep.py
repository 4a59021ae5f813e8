#!/usr/bin/python3
"""The designer's sweep: the liner's apex angle against the depth into the rock and the casing's hole.

For each full apex angle the generic charge of examples/shaped_charge_jet_formation.yaml (60 deg
as written; its cavity cut-out and 10 mm of explosive behind the apex follow the liner) forms its
jet (20 us, --formation-cell), tools/jet_table.py writes that jet as a `jet:` table (--segments
pieces of equal mass: mass, axial momentum and kinetic energy kept), and the perforation demo
(examples/jet_casing_sandstone_mpm.yaml: 8 mm casing, 15 mm cement, Berea confined at 34.5 MPa,
prestressed; its 120 mm standoff from the charge plane to the casing) fires it, to the end of the
penetration (the jet spent). Only the charge changes between the rows, as a gun designer varies it.

Collapse theory (Birkhoff, MacDougall, Pugh & Taylor 1948; thesis seed 000 ch. 3) and practice
expect a wider cone to give a slower, heavier jet: a shallower tunnel and a larger hole. What the
script checks is that trend, not values: the perforation at the deck's 1 mm cells is not converged
(docs/validation.md, "The perforation demo under refinement"), and every row says how many cells
its tip piece has across its radius.

  /usr/bin/python3 validation/apex_sweep.py --ballista build/ballista --out out/apex_sweep \\
      [--angles 40 60 80] [--formation-cell 0.25e-3] [--segments 10] [--band-cell 0.5e-3] [--threads 2]
      [--set KEY=VALUE ...]

--band-cell refines the perforation runs around the line of flight as the demo's grid study does
(validation/perforation_convergence.py): the formed jets are 0.6-1.8 mm in radius, and at the
deck's 1 mm cells none reaches the rock (the 40 deg jet, 0.7 mm at its tip, is stopped by the
casing and the cement). --set changes every perforation run. Writes sweep.json, sweep.md and
sweep.png in --out; a run whose folder holds a summary.json is not run again.
"""
import argparse
import json
import math
import os
import sys

import yaml

from case_runs import run_once, summary

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(REPO, "tools"))
from jet_table import jet_table, write_csv  # noqa: E402
from perforation_convergence import level_sets  # noqa: E402

FORMATION = os.path.join(REPO, "examples", "shaped_charge_jet_formation.yaml")
PERFORATION = os.path.join(REPO, "examples", "jet_casing_sandstone_mpm.yaml")
MOUTH_RADIUS = 0.015  # m: the example liner's mouth (30 mm)
# The refined band of --band-cell: 9 mm around the line of flight (the demo's grid study), along the
# path from 130 mm into the rock to the top of the box, where the tip piece is inserted whole.
BAND = 9.0e-3
PATH = (-30.0e-3, 190.0e-3)
BEHIND_APEX = 0.010   # m: explosive behind the apex


def run(ballista, deck, folder, sets):
    """The run into `folder` (case_runs.run_once: not again once finished); the sweep stops if it failed."""
    run_once(ballista, deck, folder, sets)
    s = summary(folder)
    if s is None or s["status"] != "completed":
        raise SystemExit(f"the run in {folder} did not complete (its summary.json, if any, says why)")
    return s


def formation_sets(angle):
    """--set arguments for a liner of this full apex angle: the cavity cut-out and the fill follow
    the cone (its height from the mouth's radius), the explosive behind the apex stays 10 mm."""
    height = MOUTH_RADIUS / math.tan(math.radians(angle / 2.0))
    return ["--set", f"bodies.1.shape.angle={angle}", "--set", f"bodies.0.cutouts.0.length={height!r}",
            "--set", f"bodies.0.shape.length={BEHIND_APEX + height!r}"]


def perforation_deck(table, out):
    """The demo deck with the formed jet's table in place of its own segments; the box reaches 60 mm
    behind the casing, for a long tip piece inserted whole 5 mm in front of it."""
    deck = yaml.safe_load(open(PERFORATION))
    jet = next(b for b in deck["bodies"] if "jet" in b)
    del jet["jet"]["segments"]
    jet["jet"]["file"] = table
    deck["grid"]["upper"] = [deck["grid"]["upper"][0], 0.19]
    # The demo's grid study is of its own jet; a table's jet is other physics (and the record's path
    # is relative to the demo's folder, not this deck's).
    deck.get("penetration", {}).pop("convergence_record", None)
    # The demo's patches sit where its own jet makes the hole, and its step per region was checked
    # with them: a table's jet runs on the study's plain levels.
    deck["grid"].pop("patches", None)
    deck["mpm"].pop("multirate", None)
    path = os.path.join(out, "perforation.yaml")
    yaml.safe_dump(deck, open(path, "w"), sort_keys=False)
    return path


def one_angle(a, angle):
    folder = os.path.join(a.out, f"apex{angle:g}")
    os.makedirs(folder, exist_ok=True)
    form = os.path.join(folder, "formation")
    run(a.ballista, FORMATION, form,
        ["--threads", str(a.threads), "--set", f"grid.cell_size={a.formation_cell!r}"] + formation_sets(angle))
    rows, rep = jet_table(form, segments=a.segments)
    table = os.path.join(folder, "jet.csv")
    write_csv(rows, table)
    sets = ["--threads", str(a.threads)]
    far = float(yaml.safe_load(open(PERFORATION))["grid"]["cell_size"])
    for s in (level_sets(a.band_cell, far, BAND, PATH) if a.band_cell else []) + a.set:
        sets += ["--set", s]
    perf = os.path.join(folder, "perforation")
    s = run(a.ballista, perforation_deck(table, folder), perf, sets)
    pen = s["penetration"]
    holes = pen.get("holes", {})
    cell = a.band_cell or float(yaml.safe_load(open(os.path.join(perf, "resolved.yaml")))["grid"]["cell_size"])
    return {
        "angle": angle,
        "jet_mass_g": 1e3 * rep["mass"],
        "jet_length_mm": 1e3 * sum(r[1] for r in rows),
        "strengthless_depth_mm": 1e3 * pen["hydrodynamic_depth"],
        "tip_velocity": rows[0][2],
        "tip_radius_mm": 1e3 * rows[0][0],
        "tip_cells_across_radius": rows[0][0] / cell,
        "depth_mm": 1e3 * pen["final_depth"],
        "cavity_depth_mm": 1e3 * pen["final_cavity_depth"],
        "casing_hole_mm": 1e3 * holes["casing"]["entrance_diameter"] if "casing" in holes else None,
        "casing_min_mm": 1e3 * holes["casing"]["min_diameter"] if "casing" in holes else None,
        "cement_hole_mm": 1e3 * holes["cement"]["entrance_diameter"] if "cement" in holes else None,
        "through_cement": bool(holes.get("cement", {}).get("perforated")) and holes["cement"]["min_diameter"] > 0,
        "tunnel_entrance_mm": 1e3 * pen["tunnel"]["entrance_diameter"] if pen.get("tunnel", {}).get(
            "entrance_diameter") else None,
        "status": s["status"],
        "wall_time_s": s["statistics"].get("wall_time"),
        "cell_mm": 1e3 * cell,
    }


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def write(a, results):
    json.dump(results, open(os.path.join(a.out, "sweep.json"), "w"), indent=1)
    lines = ["| full apex angle | jet mass (> 2 km/s), length | tip velocity | tip piece radius (cells) "
             "| strengthless depth in the rock alone | depth | cavity depth "
             "| casing hole (entrance / narrowest) | cement hole | rock tunnel entrance |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r['angle']:g}° | {r['jet_mass_g']:.2f} g, {r['jet_length_mm']:.0f} mm | "
                     f"{r['tip_velocity']:.0f} m/s | {r['tip_radius_mm']:.2f} mm ({r['tip_cells_across_radius']:.1f}) | "
                     f"{r['strengthless_depth_mm']:.0f} mm | {r['depth_mm']:.1f} mm | "
                     f"{r['cavity_depth_mm']:.1f} mm | {fmt(r['casing_hole_mm'], '.1f')} / {fmt(r['casing_min_mm'], '.1f')} mm"
                     f" | {fmt(r['cement_hole_mm'], '.1f')} mm{'' if r['through_cement'] else ' (not through)'}"
                     f" | {fmt(r['tunnel_entrance_mm'], '.1f')} mm |")
    d = [r["depth_mm"] for r in results]
    h = [r["casing_hole_mm"] for r in results]
    deeper = all(d[k + 1] < d[k] for k in range(len(d) - 1))
    wider = all(h[k] is not None and h[k + 1] is not None and h[k + 1] > h[k] for k in range(len(h) - 1))
    lines.append("")
    lines.append(f"Wider cones: shallower tunnels {'yes' if deeper else 'NO'}, larger casing holes "
                 f"{'yes' if wider else 'NO'} (the expected trend). Perforation at "
                 f"{results[0]['cell_mm']:g} mm cells around the jet: not converged (the tip pieces "
                 f"{min(r['tip_cells_across_radius'] for r in results):.1f}-"
                 f"{max(r['tip_cells_across_radius'] for r in results):.1f} cells across their radius; a rod "
                 f"needs 4).")
    open(os.path.join(a.out, "sweep.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    ang = [r["angle"] for r in results]
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
    ax[0].plot(ang, d, "o-", label="depth into the rock")
    ax[0].set_xlabel("liner's full apex angle (°)")
    ax[0].set_ylabel("depth (mm)")
    ax[0].set_title(f"depth ({results[0]['cell_mm']:g} mm cells: not converged)", fontsize=9)
    ax[1].plot(ang, h, "s-", label="casing entrance")
    ax[1].plot(ang, [r["casing_min_mm"] for r in results], "^--", label="casing narrowest")
    ax[1].set_xlabel("liner's full apex angle (°)")
    ax[1].set_ylabel("hole diameter (mm)")
    ax[1].legend(fontsize=8)
    ax[1].set_title("casing hole", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "sweep.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ballista", default="build/ballista")
    ap.add_argument("--out", default="out/apex_sweep")
    ap.add_argument("--angles", type=float, nargs="+", default=[40.0, 60.0, 80.0])
    ap.add_argument("--formation-cell", type=float, default=0.25e-3, help="m; the formation run's cells")
    ap.add_argument("--segments", type=int, default=10, help="pieces of the jet table")
    ap.add_argument("--band-cell", type=float, default=0.0,
                    help="m; cells of a band 9 mm around the line of flight in the perforation runs (the "
                         "deck's 1 mm elsewhere); 0: the deck's grid")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a deck change for every perforation run (repeatable)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    write(a, [one_angle(a, angle) for angle in a.angles])


if __name__ == "__main__":
    main()
