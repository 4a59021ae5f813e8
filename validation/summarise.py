#!/usr/bin/python3
"""Tables of the penetration validation studies (run_penetration_validation.sh OUT_DIR) as
Markdown on stdout, with the trend checks of issue 5 / thesis seed 000 ch. 5-6 marked PASS/FAIL.
Reads each run's summary.json (run_<k>/ of a sweep, or the density runs' folders)."""
import glob
import json
import math
import os
import sys

# Thesis seed 000 Table 5.3: density [g/cm3] -> penetration [cm] (none, ZeroStress, hydrodynamic).
TABLE_5_3 = {9.618: (19.08, 19.15, 30.08), 14.426: (17.34, 17.07, 24.56), 19.235: (15.54, 15.81, 21.27),
             24.044: (15.03, 15.16, 19.02), 38.470: (14.49, 14.86, 15.04)}


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def pen(summary, key):
    if not summary or summary.get("status") != "completed":
        return None
    v = (summary.get("penetration") or {}).get(key)
    return v if isinstance(v, (int, float)) and math.isfinite(v) else None


def fmt(v, scale=1.0, digits=1):
    return "—" if v is None else f"{v * scale:.{digits}f}"


def sweep_runs(folder):
    """(values of the varied keys, summary) per run of a sweep folder, in run order."""
    sj = load(os.path.join(folder, "sweep.json"))
    if not sj:
        return []
    keys = [a["key"] for a in sj["axes"]]
    out = []
    for k, run in enumerate(sj["runs"]):
        summary = load(os.path.join(folder, f"run_{k}", "summary.json"))
        out.append(({key: run.get(key) for key in keys}, summary))
    return out


def check(ok):
    return "**PASS**" if ok else "**FAIL**"


def velocity(out):
    folder = os.path.join(out, "velocity")
    fit = load(os.path.join(folder, "sweep_penetration.json"))
    if not fit:
        return
    print("### U against V (thesis §5.2, Figs. 5.11-5.12)\n")
    print("| V [m/s] | U [m/s] | U_h [m/s] | U/U_h | R − Y [GPa] |\n|---|---|---|---|---|")
    ratios = []
    for r in fit["runs"]:
        ratios.append((r["V"], r["U_over_Uh"]))
        print(f"| {r['V']:.0f} | {r['U']:.0f} | {r['U_h']:.0f} | {r['U_over_Uh']:.3f} | {fmt(r.get('R_minus_Y'), 1e-9, 2)} |")
    ratios.sort()
    rising = all(b[1] >= a[1] - 0.02 for a, b in zip(ratios, ratios[1:]))
    below = all(x[1] < 1.0 for x in ratios)
    print(f"\nFit U = a + bV: a = {fit['a']:.0f} m/s, b = {fit['b']:.3f}, r² = {fit['r2']:.4f} "
          f"(hydrodynamic slope {fmt(fit.get('hydrodynamic_slope'), 1, 3)}); curvature eq. 5.5 = "
          f"{fmt(fit.get('curvature'), 1, 0)} kg/m³, V_m = {fmt(fit.get('extremum_velocity'), 1, 0)} m/s.\n")
    print(f"- U linear in V, r² ≥ 0.99: {check(fit['r2'] >= 0.99)}")
    print(f"- U/U_h below 1 and rising with V (within 0.02): {check(rising and below)}\n")


def density(out):
    rows = []
    for d in sorted(glob.glob(os.path.join(out, "density", "rho_*"))):
        s = load(os.path.join(d, "summary.json"))
        rho = float(d.rsplit("_", 1)[1])
        rows.append((rho, pen(s, "penetrator_length"), pen(s, "max_depth"), pen(s, "hydrodynamic_depth")))
    if not rows:
        return
    rows.sort()
    print("### Depth against rod density at fixed mass (thesis Table 5.3)\n")
    print("| ρ_p [kg/m³] | L [mm] | P [mm] | P_hydro [mm] | P/P_hydro | thesis P/P_hydro (none, ZeroStress) |")
    print("|---|---|---|---|---|---|")
    for rho, L, P, Ph in rows:
        t = TABLE_5_3.get(round(rho / 1000, 3))
        ratio = P / Ph if P is not None and Ph else None
        th = f"{t[0] / t[2]:.2f}, {t[1] / t[2]:.2f}" if t else "—"
        print(f"| {rho:.0f} | {fmt(L, 1e3)} | {fmt(P, 1e3)} | {fmt(Ph, 1e3)} | {fmt(ratio, 1, 2)} | {th} |")
    ok = [r for r in rows if r[2] is not None and r[3]]
    if len(ok) >= 2:
        ratios = [r[2] / r[3] for r in ok]
        print(f"\n- P/P_hydro rises with density (Table 5.3 trend): "
              f"{check(all(b >= a - 0.02 for a, b in zip(ratios, ratios[1:])))}\n")


def confinement(out):
    runs = sweep_runs(os.path.join(out, "confinement"))
    if not runs:
        return
    print("### Depth against confinement, drained and saturated (thesis Table 5.5)\n")
    table = {}
    for vals, s in runs:
        preset = str(vals.get("materials.rock.preset"))
        p = float(vals.get("loads.0.pressure"))
        table.setdefault(preset, {})[p] = pen(s, "max_depth")
    pressures = sorted({p for t in table.values() for p in t})
    print("| target | " + " | ".join(f"{p / 1e6:.1f} MPa" for p in pressures) + " |")
    print("|---|" + "---|" * len(pressures))
    for preset, t in table.items():
        print(f"| {preset} | " + " | ".join(fmt(t.get(p), 1e3) + " mm" for p in pressures) + " |")
    falls = all(all(t.get(b) is not None and t.get(a) is not None and t[b] <= t[a] for a, b in zip(pressures, pressures[1:]))
                for t in table.values())
    d, s = table.get("sandstone_berea_drained", {}), table.get("sandstone_berea_saturated", {})
    deeper = all(d.get(p) is not None and s.get(p) is not None and s[p] > d[p] for p in pressures)
    print(f"\n- depth falls with confinement: {check(falls)}")
    print(f"- saturated deeper than drained at every confinement: {check(deeper)}\n")


BILLET_THICKNESS = 0.0495  # m, examples/rod_billet_4130_mpm.yaml (thesis §6.4)


def exit_energy(folder):
    """(time, penetrator kinetic energy) when the deepest penetrator particle first passes the
    billet's back face, from history.csv; None if it never does."""
    try:
        import numpy as np
        d = np.genfromtxt(os.path.join(folder, "history.csv"), delimiter=",", names=True)
        crossed = np.nonzero(d["penetration_depth"] > BILLET_THICKNESS)[0]
        if len(crossed) == 0:
            return None
        i = crossed[0]
        return float(d["penetration_time"][i]), float(d["penetrator_kinetic_energy"][i])
    except (OSError, ValueError, KeyError):
        return None


def segmented(out):
    folder = os.path.join(out, "segmented")
    runs = sweep_runs(folder)
    if not runs:
        return
    print("### Solid against segmented rod into the 4130 billet (thesis §6.4, Table 6.5)\n")
    print("| rod | depth [mm] | perforated | at the back face: time [µs], penetrator KE [J] | thesis depth (none / ZeroStress) [mm] |")
    print("|---|---|---|---|---|")
    depth, exits = {}, {}
    for k, (vals, s) in enumerate(runs):
        ld = float(vals.get("bodies.1.rod.segment_ld"))
        name = "solid" if ld == 0 else f"segmented, L/D = {ld:g}"
        depth[ld] = pen(s, "max_depth")
        exits[ld] = exit_energy(os.path.join(folder, f"run_{k}"))
        perforated = depth[ld] is not None and depth[ld] > BILLET_THICKNESS
        e = exits[ld]
        thesis = "47.6 / 52.3" if ld == 0 else "41.1 / 54.8"
        print(f"| {name} | {fmt(depth[ld], 1e3)} | {'yes' if perforated else 'no'} | "
              f"{'—' if e is None else f'{e[0] * 1e6:.1f}, {e[1]:.0f}'} | {thesis} |")
    if len(depth) == 2 and None not in depth.values():
        solid, seg = depth[0.0], [v for k, v in depth.items() if k != 0.0][0]
        if solid > BILLET_THICKNESS and seg > BILLET_THICKNESS:
            es, eg = exits[0.0], [v for k, v in exits.items() if k != 0.0][0]
            print("\n- segmented rod deeper than the solid rod: **NOT TESTABLE** (both perforate the billet)")
            if es and eg:
                print(f"- segmented rod keeps more kinetic energy at the back face: {check(eg[1] > es[1])} "
                      f"({eg[1]:.0f} J against {es[1]:.0f} J)\n")
        else:
            print(f"\n- segmented rod deeper than the solid rod: {check(seg > solid)}\n")


def resolution(out):
    runs = sweep_runs(os.path.join(out, "resolution"))
    rows = sorted(((float(v.get("grid.cell_size")), pen(s, "max_depth"), pen(s, "steady_rate")) for v, s in runs),
                  reverse=True)
    if len(rows) < 3 or any(r[1] is None or r[2] is None for r in rows):
        return
    print("### Grid convergence (unconfined, 3.3 km/s)\n")
    print("| cell size [mm] | depth [mm] | U [m/s] |\n|---|---|---|")
    for h, P, U in rows:
        print(f"| {h * 1e3:g} | {P * 1e3:.2f} | {U:.0f} |")
    for name, k in (("depth", 1), ("rate", 2)):
        d1, d2 = rows[1][k] - rows[0][k], rows[2][k] - rows[1][k]
        ok = d1 != 0 and d2 != 0 and d1 / d2 > 0
        order = math.log(d1 / d2, rows[0][0] / rows[1][0]) if ok else None
        print(f"\n- observed order of the {name} (three grids): {fmt(order, 1, 2)}")
    print()


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/validation"
    print(f"## Penetration validation ({out})\n")
    for study in (velocity, density, confinement, segmented, resolution):
        study(out)


if __name__ == "__main__":
    main()
