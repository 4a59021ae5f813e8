#!/usr/bin/python3
"""Thesis seed 000, Table 5.4 and Fig. 5.21: depth under an anisotropic overburden. At the same
mean stress e = (sigma_axial + 2 sigma_radial) / 3 (thesis eq. 5.6), a target loaded harder along
the line of flight than across it should be penetrated deeper, and one loaded harder across it
shallower, than under the isotropic state (the experimental trend the thesis cites as its
ref. [74]; its Arenisca runs showed it at e = 2 and 6 ksi, not at 4 ksi).

The thesis ran this study with its discrete jet; Ballista's analogue is the demo's ten-segment
copper jet into the confined rock alone (validation/jet_train_sandstone.yaml, its target widened to 60 mm), here in the
thesis's drained sandstone as far as the thesis states it (sandstone_thesis_drained). Each row is one run:
the confinement load's `axial` and `radial` tractions, ramped and damped to equilibrium in the
overburden stage, then the jet.

  /usr/bin/python3 validation/thesis_table_5_4.py --ballista build/ballista --out out/table_5_4 \\
      [--cell 0.5e-3] [--tests 0,1,2,...] [--threads 1] [--set KEY=VALUE ... --tag NAME]

--cell refines a band around the jet's path (as validation/perforation_convergence.py; 2 mm
elsewhere): 1 mm is 1 cell across the tip's radius (3-5 min a run on one thread), 0.5 mm 2
cells (18-25 min). Test 0 is the unconfined reference (the thesis's large black circle); tests 10 and 11
repeat test 6 (isotropic, 4 ksi) with its tractions changed by one part in 10^9 and by 1 %, test
12 test 9 (isotropic, 6 ksi) by 1 %: how far round-off alone moves the depth, and whether the
depth follows a small change smoothly. A run whose folder holds a summary.json is not run again.
"""
import os
import sys

from case_runs import add_deck_changes, after_firing, parse_study, run_once, state, study_arguments, summary
from perforation_convergence import level_sets

DECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "jet_train_sandstone.yaml")
KSI = 6.894757e6  # Pa
# Thesis Table 5.4: test number -> (sigma_axial, sigma_radial) in ksi; e from eq. 5.6.
TESTS = {1: (4, 1), 2: (0, 3), 3: (2, 2),
         4: (8, 2), 5: (0, 6), 6: (4, 4),
         7: (10, 4), 8: (2, 8), 9: (6, 6)}
REFERENCE = 0      # unconfined
# Test 6 again with its tractions scaled: by 1 + 1e-9 (what round-off alone moves), and by 1.01
# (a change the depth should follow smoothly, by about 1 % of the confinement's own effect).
NOISE = 10
NOISE_SCALE = 1.0 + 1.0e-9
NUDGE = 11
NUDGE_SCALE = 1.01
NUDGE_9 = 12       # test 9 (isotropic, 6 ksi) by 1.01: the roughness where the 0.5 mm level ran
# The deck's 30 mm target is widened to 60 mm (12 tunnel radii; at 30 mm the outer surface next
# to the crater bulged and a loaded point there inverted under 4 ksi axial and 1 ksi radial, Berea)
# at no extra cost: --cell applies within BAND of the line of flight and along the jet's path
# through the 200 mm rock (PATH, as docs/validation.md's grid study of this deck), FAR beyond.
RADIUS = 0.06
BAND = 15.0e-3
PATH = (0.04, 0.235)
FAR = 2.0e-3
TIMES = [40e-6, 70e-6, 100e-6]


def tractions(test):
    """(axial, radial) in Pa."""
    if test == REFERENCE:
        return 0.0, 0.0
    if test in (NOISE, NUDGE, NUDGE_9):
        ax, rad = TESTS[9 if test == NUDGE_9 else 6]
        scale = NOISE_SCALE if test == NOISE else NUDGE_SCALE
        return ax * KSI * scale, rad * KSI * scale
    ax, rad = TESTS[test]
    return ax * KSI, rad * KSI


def mean_stress_ksi(test):
    ax, rad = tractions(test)
    return (ax + 2 * rad) / 3 / KSI


def folder(out, cell, test, tag):
    return os.path.join(out, f"h_{1e3 * cell:g}mm", f"test{test}" + (f"_{tag}" if tag else ""))


def run(a, test):
    ax, rad = tractions(test)
    sets = ["--set", "materials.rock.preset=sandstone_thesis_drained",
            "--set", f"loads.0.pressure={rad!r}", "--set", f"loads.0.radial={rad!r}",
            "--set", f"loads.0.axial={ax!r}", "--set", f"loads.0.hole_radius={a.hole_radius!r}",
            # The deck's 99.8 % is not reached under 2 ksi axial and 8 ksi radial within 600 us
            # (99.72 % at 1 mm; the outliers are corner particles, where the two tractions meet);
            # every test ends its preload by the same rule.
            "--set", "stages.0.until.fraction=0.995"]
    sets += ["--set", f"bodies.0.shape.radius={RADIUS!r}", "--set", f"grid.upper=[{RADIUS + 5 * FAR!r}, 0.25]"]
    for s in level_sets(a.cell, FAR, BAND, PATH):
        sets += ["--set", s]
    for s in a.set:
        sets += ["--set", s]
    sets += ["--threads", str(a.threads)]
    run_once(a.ballista, DECK, folder(a.out, a.cell, test, a.tag), sets)


def final_cavity(s):
    """The final cavity depth [m] of a run's summary (the deepest jet point can be one point driven
    ahead of the cavity's bottom; docs/validation.md, the grid study of this deck), or None."""
    if s is None or s["status"] != "completed":
        return None
    return s["penetration"]["final_cavity_depth"]


def cavity(out, cell, test, tag):
    return final_cavity(summary(folder(out, cell, test, tag)))


def main():
    ap = study_arguments(__doc__, "out/table_5_4")
    ap.add_argument("--cell", type=float, default=1.0e-3, help="cell size along the jet's path, m")
    ap.add_argument("--tests", default=",".join(str(t) for t in [REFERENCE] + sorted(TESTS) + [NOISE, NUDGE, NUDGE_9]))
    # No hole by default: under a 6 mm hole 6-8 % of the particles (most of them in the refined
    # band) stay outside +-5 % of an axial load, and the preload never ends.
    add_deck_changes(ap)
    ap.add_argument("--threads", type=int, default=2, help="threads of each run (bitwise the same answer)")
    a = parse_study(ap)
    tests = [int(t) for t in a.tests.split(",")]
    if not a.table_only:
        for t in tests:
            run(a, t)

    ref = cavity(a.out, a.cell, REFERENCE, a.tag)
    print(f"Cavity depth [mm] at {1e3 * a.cell:g} mm cells along the path (change from unconfined); "
          "the preload stage's length [us]")
    print()
    print("| test | axial [ksi] | radial [ksi] | e [ksi] | depth | " +
          " | ".join(f"at {1e6 * t:.0f} us" for t in TIMES) + " | preload |")
    print("|---|---|---|---|---|" + "---|" * len(TIMES) + "---|")
    for t in [REFERENCE] + sorted(TESTS) + [NOISE, NUDGE, NUDGE_9]:
        f = folder(a.out, a.cell, t, a.tag)
        s = summary(f)
        if s is None:
            continue
        p = final_cavity(s)
        ours = state(f) if p is None else (f"{1e3 * p:.1f}" + ("" if t == REFERENCE or ref is None
                                                                else f" ({p / ref - 1:+.1%})"))
        ax, rad = tractions(t)
        stages = s.get("stages", [])
        pre = f"{1e6 * (stages[0]['end_time'] - stages[0]['start_time']):.0f}" if stages else ""
        hist = after_firing(f, "cavity_depth", TIMES)
        name = {REFERENCE: "unconfined", NOISE: "6, tractions x (1 + 1e-9)", NUDGE: "6, tractions x 1.01",
                NUDGE_9: "9, tractions x 1.01"}.get(t, str(t))
        print(f"| {name} | {ax / KSI:g} | {rad / KSI:g} | {mean_stress_ksi(t):.0f} | {ours} | " +
              " | ".join("" if v is None else f"{1e3 * v:.1f}" for v in hist) + f" | {pre} |")

    # The trend at each mean stress: axial-heavy deepest, radial-heavy shallowest.
    print()
    print("| e [ksi] | axial-heavy | isotropic | radial-heavy | expected order (axial > iso > radial) |")
    print("|---|---|---|---|---|")
    for e, (up, iso, down) in {2: (1, 3, 2), 4: (4, 6, 5), 6: (7, 9, 8)}.items():
        d = [cavity(a.out, a.cell, t, a.tag) for t in (up, iso, down)]
        if any(v is None for v in d):
            continue
        order = "yes" if d[0] > d[1] > d[2] else "no"
        print(f"| {e} | " + " | ".join(f"{1e3 * v:.1f}" for v in d) + f" | {order} |")
    for base, t, what in ((6, NOISE, "by 1e-9 (round-off)"), (6, NUDGE, "by 1 %"), (9, NUDGE_9, "by 1 %")):
        pair = [cavity(a.out, a.cell, k, a.tag) for k in (base, t)]
        if None not in pair:
            print(f"\nTest {base} with its tractions changed {what}: {1e3 * pair[0]:.2f} and {1e3 * pair[1]:.2f} mm "
                  f"({pair[1] / pair[0] - 1:+.3%})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
