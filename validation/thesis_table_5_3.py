#!/usr/bin/python3
"""Thesis seed 000, Table 5.3 at the thesis's scale: rods of equal mass, momentum and energy (10 g,
33 N s, 54.5 kJ: D 3 mm, 3.3 km/s, length in inverse proportion to density) into the thesis's
sandstone as far as the thesis states it (sandstone_thesis_drained) in its 0.2 m target.

  /usr/bin/python3 validation/thesis_table_5_3.py --ballista build/ballista --out out/table_5_3 [--rows 1,5]

Each row runs examples/rod_sandstone_mpm.yaml to 500 us (~15 min on 2 cores); a row whose folder
already holds a summary.json is not run again (--table-only: run nothing). The thesis's P/P_h rises
with the rod's density, from 0.63 to 0.96-0.99.
"""
import os
import sys

from case_runs import final_depth, run_once, state, study_arguments

DECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "rod_sandstone_mpm.yaml")
# The thesis's target and rock (the catalogue's rod problem and validation/thesis_rod_causes.py run
# row 3 with the same settings).
THESIS = ["--set", "materials.rock.preset=sandstone_thesis_drained", "--set", "bodies.0.shape.radius=0.2",
          "--set", "simulation.end_time=500e-6"]
EXAMPLE_ROD_LENGTH = 73.54e-3  # m; the example's grid ends 6.5 mm above this rod's tail


def grid_upper(length):
    """The grid's top, lengthened with a rod longer than the example's."""
    return 0.332 + max(0.0, length - EXAMPLE_ROD_LENGTH)
# Table 5.3: rod density [kg/m^3], length [m], depth with erosion none and ZeroStress [m].
ROWS = [
    (9618, 147.08e-3, 0.1908, 0.1915),
    (14426, 98.05e-3, 0.1734, 0.1707),
    (19235, 73.54e-3, 0.1554, 0.1581),
    (24044, 58.83e-3, 0.1503, 0.1516),
    (38470, 36.78e-3, 0.1449, 0.1486),
]
TARGET_DENSITY = 2300.0  # kg/m^3, the thesis's (its hydrodynamic column is L sqrt(rho_p / 2300))


def folder(out, k):
    return os.path.join(out, f"row{k}")


def run(ballista, out, k):
    rho, length, _, _ = ROWS[k - 1]
    run_once(ballista, DECK, folder(out, k), THESIS + [
        "--set", f"grid.upper=[0.205,{grid_upper(length):.5f}]",
        "--set", f"materials.rod.density={rho}", "--set", f"bodies.1.rod.length={length}"])


def main():
    ap = study_arguments(__doc__, "out/table_5_3")
    ap.add_argument("--rows", default="1,2,3,4,5", help="rows of Table 5.3 to run, 1-5")
    a = ap.parse_args()
    rows = [int(k) for k in a.rows.split(",")]
    if not a.table_only:
        for k in rows:
            run(a.ballista, a.out, k)
    print("| ρ_p [kg/m³] | L [mm] | P_h [mm] | Ballista P [mm] | P/P_h | thesis P, none / ZeroStress [mm] | thesis P/P_h |")
    print("|---|---|---|---|---|---|---|")
    for k, (rho, length, none, zero) in enumerate(ROWS, start=1):
        ph = length * (rho / TARGET_DENSITY) ** 0.5
        p = final_depth(folder(a.out, k))
        ours = f"{state(folder(a.out, k))} | " if p is None else f"{1000 * p:.1f} | {p / ph:.3f}"
        print(f"| {rho} | {1000 * length:.2f} | {1000 * ph:.1f} | {ours} | {1000 * none:.1f} / {1000 * zero:.1f} "
              f"| {none / ph:.3f} / {zero / ph:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
