#!/usr/bin/python3
"""The charge and the well in one run against the jet handed on by a table.

examples/shaped_charge_perforation.yaml forms its jet and fires it through the casing, the cement
and the confined rock in one run. The other way a designer can go from a charge to a hole is in two
steps: write the formed jet as a `jet:` table (tools/jet_table.py: pieces of equal mass, mass, axial
momentum and kinetic energy kept) and fire the table through the perforation demo's target
(examples/jet_casing_sandstone_mpm.yaml: the same casing, cement and rock at the same 120 mm from
the charge plane). This script does the second from the first: it takes the one run's own jet at
--time (formed and in free flight, before its tip reaches the casing), fires it as a table at the
demo's 0.5 mm cells along the flight (the one run's), and prints the two runs' depth and holes side
by side. What the table leaves out is what the comparison measures: the products behind the jet,
the slug and the liner slower than 2 km/s, and the velocity spread inside each piece.

  /usr/bin/python3 validation/charge_handoff.py --ballista build/ballista --out out/handoff \\
      [--one-run DIR] [--time 20e-6] [--segments 10] [--threads 2]

--one-run reads a run of the example (the script runs it into that folder, or OUT/one_run, if it has
not run). Writes
handoff.json and handoff.md in --out; a run whose folder holds a summary.json is not run again.
"""
import argparse
import json
import os
import sys

from apex_sweep import perforation_deck, run

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(REPO, "tools"))
from jet_table import jet_table, write_csv  # noqa: E402

ONE_RUN = os.path.join(REPO, "examples", "shaped_charge_perforation.yaml")


def readings(s):
    """The numbers a designer reads from a run's summary (mm; None where not measured)."""
    pen = s["penetration"]
    holes = pen.get("holes", {})

    def mm(v):
        return None if v is None else 1e3 * v

    def hole(layer, key):
        return mm(holes.get(layer, {}).get(key))

    return {
        "cavity_depth": mm(pen.get("final_cavity_depth")),
        "deepest_point": mm(pen.get("max_depth")),
        "tunnel_entrance": mm((pen.get("tunnel") or {}).get("entrance_diameter")),
        "casing_hole_mean": hole("casing", "mean_diameter"),
        "casing_hole_entrance": hole("casing", "entrance_diameter"),
        "cement_hole_entrance": hole("cement", "entrance_diameter"),
        "steps": s["statistics"]["steps"],
        "wall_time": s["statistics"]["wall_time"],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ballista", default=os.path.join(REPO, "build", "ballista"))
    ap.add_argument("--out", required=True)
    ap.add_argument("--one-run", help="a run of examples/shaped_charge_perforation.yaml (run into it if it has not run)")
    ap.add_argument("--time", type=float, default=20.0e-6,
                    help="when the jet is written as a table, s after the detonator (its tip reaches the casing "
                         "at about 27 us)")
    ap.add_argument("--segments", type=int, default=10, help="pieces of equal mass in the table")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    one = a.one_run or os.path.join(a.out, "one_run")
    s_one = run(a.ballista, ONE_RUN, one, ["--threads", str(a.threads)])
    # The charge plane is the liner's mouth (jet_table's default), 120 mm in front of the casing as
    # in the demo's table (its standoff).
    rows, rep = jet_table(one, time=a.time, segments=a.segments)
    table = os.path.join(a.out, "jet.csv")
    write_csv(rows, table)
    folder = os.path.join(a.out, "table_run")
    s_tab = run(a.ballista, perforation_deck(table, a.out), folder, ["--threads", str(a.threads)])
    one_r, tab_r = readings(s_one), readings(s_tab)
    result = {"time": a.time, "jet_mass": rep["mass"], "pieces": len(rows), "tip_velocity": rows[0][2],
              "tip_radius": rows[0][0], "one_run": one_r, "table": tab_r}
    json.dump(result, open(os.path.join(a.out, "handoff.json"), "w"), indent=1)

    def fmt(v, spec=".1f"):
        return "—" if v is None else format(v, spec)

    def diff(k):
        x, y = one_r[k], tab_r[k]
        return "—" if x is None or y is None or x == 0 else f"{100.0 * (y - x) / x:+.1f} %"

    names = [("cavity_depth", "cavity depth (mm)"), ("deepest_point", "deepest jet point (mm)"),
             ("tunnel_entrance", "rock tunnel entrance (mm)"), ("casing_hole_mean", "casing hole, averaged (mm)"),
             ("casing_hole_entrance", "casing hole, entrance slice (mm)"),
             ("cement_hole_entrance", "cement hole entrance (mm)")]
    lines = [f"The jet at {a.time * 1e6:g} us: {1e3 * rep['mass']:.3g} g faster than 2 km/s in {len(rows)} pieces, "
             f"tip {rows[0][2]:.0f} m/s, tip piece radius {1e3 * rows[0][0]:.2f} mm.", "",
             "| | one run (charge to rock) | the jet as a table | table against one run |", "|---|---|---|---|"]
    lines += [f"| {label} | {fmt(one_r[k])} | {fmt(tab_r[k])} | {diff(k)} |" for k, label in names]
    lines.append(f"| steps, wall time | {one_r['steps']}, {one_r['wall_time']:.0f} s | {tab_r['steps']}, "
                 f"{tab_r['wall_time']:.0f} s | |")
    text = "\n".join(lines) + "\n"
    open(os.path.join(a.out, "handoff.md"), "w").write(text)
    print(text)


if __name__ == "__main__":
    main()
