#!/usr/bin/python3
"""Thesis seed 000, Table 6.8 (rod rows): a pure tungsten rod, D 2.9 mm, L 79.5 mm, 3266 m/s
(10.1 g, 33 N s, 54 kJ), into the thesis's sandstone as far as it is stated, in its narrow free
target (0.0508 m in diameter, §6.4), erosion none and ZeroStress on the penetrator, to 500 us.

  /usr/bin/python3 validation/thesis_table_6_8.py --ballista build/ballista --out out/table_6_8

The thesis's rods went past the hydrodynamic depth (25.85 and 25.71 cm against P_h = 23.0 cm),
which it put down to the target: "too small a diameter (0.0508 m) for use with a free surface
condition". The target's length is not stated; 0.35 m holds the thesis's depths. The ZeroStress
rod's points erode when they lose Drucker stability (thesis eq. 6.9): the thesis does not say which
of its failure criteria (eq. 6.5-6.10) eroded its rods, but Uintah's tungsten of the thesis's
density (MaterialData/W.xml, 19,235 kg/m^3) carries the Drucker stability check and no other.
(Melting, eq. 6.6, never happens here: with Johnson-Cook thermal softening the flow stress, and
so the plastic heating, vanishes as T approaches T_m.) The discrete-jet rows are not run: the
thesis gives its jet's segments as plots only (Figs. 5.3-5.4). A run whose folder already holds a
summary.json is not run again (--table-only: run nothing). --set changes the deck of every run and
--tag names its folders apart; --erosion picks the rows. The 0.5 mm level of the erosion-none row
(docs/validation.md, 40 minutes on 2 cores):

  /usr/bin/python3 validation/thesis_table_6_8.py --ballista build/ballista --out out/table_6_8 \
      --erosion none --set grid.cell_size=0.5e-3 --tag h05
"""
import os
import sys

from case_runs import run_once, state, study_arguments, summary

DECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "rod_sandstone_thesis.yaml")
RADIUS, TARGET_LENGTH = 0.0254, 0.35  # m
# The free target (1.6 kg) takes the rod's 33 N s and moves ~10 mm in 500 us: grid below its base.
GRID_BELOW = 0.03  # m
ROD = {"diameter": 2.9e-3, "length": 79.5e-3, "speed": 3266.0, "density": 19235.0}
TARGET_DENSITY = 2300.0
# Table 6.8, depth [m] with the penetrator's erosion none and ZeroStress.
THESIS = {"none": 0.2585, "zero_stress": 0.2571}
ZERO_STRESS = "materials.rod.failure={criterion: drucker_stability, erosion: zero_stress}"
EROSION = {"none": [], "zero_stress": ["--set", ZERO_STRESS]}


def folder(out, erosion, tag):
    return os.path.join(out, erosion + (f"_{tag}" if tag else ""))


def run(ballista, out, erosion, sets=(), tag=""):
    nose = TARGET_LENGTH + 2.0e-3
    top = nose + ROD["length"] + 6.5e-3
    extra = [a for kv in sets for a in ("--set", kv)]
    run_once(ballista, DECK, folder(out, erosion, tag), [
           "--set", f"bodies.0.shape.radius={RADIUS}", "--set", f"bodies.0.shape.length={TARGET_LENGTH}",
           "--set", f"grid.lower=[0,{-GRID_BELOW}]", "--set", f"grid.upper=[{RADIUS + 5e-3:.6g},{top:.6g}]", "--set", f"bodies.1.rod.nose=[0,{nose:.6g}]",
           "--set", f"bodies.1.rod.diameter={ROD['diameter']}", "--set", f"bodies.1.rod.length={ROD['length']}",
           "--set", f"bodies.1.rod.speed={ROD['speed']}", "--set", f"materials.rod.density={ROD['density']}",
           "--set", "simulation.end_time=500e-6"] + EROSION[erosion] + extra)


def main():
    ap = study_arguments(__doc__, "out/table_6_8")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a deck change for every run (repeatable; needs --tag)")
    ap.add_argument("--tag", default="", help="appended to the run folders' names")
    ap.add_argument("--erosion", default=",".join(EROSION), help="the rows to run: none, zero_stress")
    a = ap.parse_args()
    if a.set and not a.tag:
        ap.error("--set needs --tag, so that its runs do not mix with the deck's own")
    rows = [e for e in a.erosion.split(",") if e]
    for e in rows:
        if e not in EROSION:
            ap.error(f"--erosion: unknown row '{e}' (none, zero_stress)")
    if not a.table_only:
        for erosion in rows:
            run(a.ballista, a.out, erosion, a.set, a.tag)
    ph = ROD["length"] * (ROD["density"] / TARGET_DENSITY) ** 0.5
    print(f"P_h = {1000 * ph:.1f} mm")
    print("| penetrator erosion | Ballista P [mm] | P/P_h | thesis P [mm] | thesis P/P_h |")
    print("|---|---|---|---|---|")
    for erosion in rows:
        ref = THESIS[erosion]
        s = summary(folder(a.out, erosion, a.tag))
        if s is None or s["status"] != "completed":
            ours = f"{state(folder(a.out, erosion, a.tag))} | "
        elif s["penetration"]["max_depth"] > TARGET_LENGTH:  # the rod went through and off the grid
            ours = f"through the {TARGET_LENGTH:g} m target | "
        else:
            p = s["penetration"]["final_depth"]
            ours = f"{1000 * p:.1f} | {p / ph:.3f}"
        print(f"| {erosion} | {ours} | {1000 * ref:.1f} | {ref / ph:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
