#!/usr/bin/python3
"""The expanding ring against the energy theory of fragment size: count against expansion velocity.

Runs examples/pd_expanding_ring.yaml (a 4340 ring, radius 45-50 mm, micro-plastic bonds) at several
radial velocities and lattice spacings, with the bonds' own work to separation as the fracture
energy (`peridynamics.fracture_work: bond_law`, so that the energy a crack takes is the deck's G0),
until the ring's nominal hoop strain v t / R reaches --strain, and counts the fragments of at least
--min-mass (the lattice's loose points left out) at the end; a count that still grew in the run's
last twelfth is marked.

Beside each count, two theories of the mean fragment length s of a ring stretching at the rate
eps_dot = v / R (R the mean radius), N = 2 pi R / s:

  energy (Grady, J. Appl. Phys. 53 (1982) 322; Grady, Fragmentation of Rings and Shells, Springer
  2006, ch. 2): a fragment of length s breaks free when the kinetic energy of its motion about its
  own centre, rho A eps_dot^2 s^3 / 24, pays for one crack, G0 A:
      s = (24 G0 / (rho eps_dot^2))^(1/3),  so  N grows as v^(2/3);
  energy with the elastic energy (after Glenn & Chudnovsky, J. Appl. Phys. 59 (1986) 1379): the
  ring flows at its flow stress Y, and a fragment that breaks free unloads, giving up
  Y^2 / (2 E) per unit volume (E the bonds' uniaxial modulus) to the crack as well. Y is the
  plateau the micro-plastic bonds flow at in uniaxial stress, 1.4115 times their first yield
  (`yield_stress`) in 2D (src/peridynamics/bond_constants.hpp, micro_plastic_flow_factor), or the
  deck's `flow_stress`:
      rho eps_dot^2 s^3 / 24 + Y^2 s / (2 E) = G0,  the real root of the cubic; at low rates s tends
      to 2 E G0 / Y^2, a ceiling on the fragment length that the kinetic term alone does not have;
  Mott (Proc. R. Soc. A 189 (1947) 300): release waves from each break unload a length that grows
  with time; with a fracture strain scattered as exp(gamma eps),
      s = sqrt(2 Y / (rho gamma)) / eps_dot,  so  N grows as v.
      gamma is not a property of the deck (its flaws are a normal scatter of the critical stretch),
      so only Mott's exponent is compared; the script reports the gamma that fits the counts.

The observed exponent p of N = a v^p (least squares in log-log) is reported per lattice, with the
spread of the counts over --seeds draws of the flaws (`peridynamics.scatter_seed`) at the coarsest
lattice.

Usage: validation/expanding_ring_theory.py --ballista build/ballista --out DIR
           [--velocities 100 150 200 300 450 600] [--cells 5e-4 2.5e-4] [--seeds 3] [--threads 1]
Writes DIR/ring_theory.json, DIR/ring_theory.md (the table of docs/validation.md) and
DIR/ring_count_velocity.png. About 20 minutes on one core with the defaults.
"""
import argparse
import collections
import csv
import json
import math
import os
import subprocess

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "..", "examples", "pd_expanding_ring.yaml")


def flow_factor_2d():
    """The 2D micro-plastic plateau over the first yield, (6/pi)(phi0 - pi/4 + sin(2 phi0)/2) with
    phi0 - sin(2 phi0)/2 = pi/4 (bond_constants.hpp, micro_plastic_flow_factor): 1.4115."""
    phi = 1.15
    for _ in range(8):
        phi -= (phi - 0.5 * math.sin(2 * phi) - 0.25 * math.pi) / (1.0 - math.cos(2 * phi))
    return 6.0 / math.pi * (phi - 0.25 * math.pi + 0.5 * math.sin(2 * phi))


def ring_data(deck_path):
    """Density, fracture energy, flow stress, mean radius and circumference of the example's ring."""
    with open(deck_path) as f:
        d = yaml.safe_load(f)
    body = d["bodies"][0]
    mat = d["materials"][body["material"]]
    pd = d["peridynamics"]
    r_mean = 0.5 * (body["shape"]["radius"] + body["shape"]["inner_radius"])
    # The bonds' uniaxial modulus in plane stress: 4/3 of the dilatational modulus E / (2 (1 - nu))
    # they are calibrated to (src/peridynamics/bond_constants.cpp, dilatational_modulus, yield_stretch).
    k, g = float(mat["bulk_modulus"]), float(mat["shear_modulus"])
    e = 9.0 * k * g / (3.0 * k + g)
    nu = (3.0 * k - 2.0 * g) / (2.0 * (3.0 * k + g))
    return {"density": float(mat["density"]), "G0": float(d["peridynamics"]["fracture_energy"]),
            "yield_stress": float(pd["yield_stress"]) if "yield_stress" in pd else None, "R": r_mean,
            "flow_stress": float(pd["flow_stress"]) if "flow_stress" in pd else flow_factor_2d() * float(pd["yield_stress"]),
            "E_bonds": 4.0 / 3.0 * e / (2.0 * (1.0 - nu))}


def grady_count(ring, v):
    """Energy balance (module docstring): N = 2 pi R / (24 G0 / (rho eps_dot^2))^(1/3)."""
    rate = v / ring["R"]
    s = (24.0 * ring["G0"] / (ring["density"] * rate * rate)) ** (1.0 / 3.0)
    return 2.0 * math.pi * ring["R"] / s


def elastic_energy_count(ring, v):
    """Kinetic and elastic energy against one crack (module docstring): the root of
    a s^3 + b s = G0, a = rho eps_dot^2 / 24, b = Y^2 / (2 E), by bisection (the left side grows with s)."""
    rate = v / ring["R"]
    a = ring["density"] * rate * rate / 24.0
    b = ring["flow_stress"] ** 2 / (2.0 * ring["E_bonds"])
    lo, hi = 0.0, ring["G0"] / b
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if a * mid ** 3 + b * mid < ring["G0"] else (lo, mid)
    return 2.0 * math.pi * ring["R"] / (0.5 * (lo + hi))


def counts_by_time(path, min_mass):
    c = collections.Counter()
    with open(path) as f:
        for row in csv.DictReader(f):
            if float(row["mass"]) >= min_mass:
                c[float(row["time"])] += 1
    return sorted(c.items())


def run(a, v, cell, seed, ring):
    end = a.strain * ring["R"] / v
    reach = ring["R"] * (1.0 + a.strain) + 0.05  # the ring's radius at the end, and room for its spread
    out = os.path.join(a.out, f"v{v:g}_h{cell * 1e3:g}mm_seed{seed}")
    summary = os.path.join(out, "summary.json")
    if not (a.reuse and os.path.exists(summary)):
        cmd = [a.ballista, "run", DECK, "-o", out, "-q", "--no-plots", "--overwrite", "--threads", str(a.threads),
               "--set", f"bodies.0.radial_velocity={v}", "--set", f"simulation.end_time={end}",
               "--set", f"grid.cell_size={cell}", "--set", f"grid.lower=[{-reach},{-reach}]",
               "--set", f"grid.upper=[{reach},{reach}]", "--set", "peridynamics.fracture_work=bond_law",
               "--set", f"peridynamics.fragment_interval={end / 12}", "--set", f"output.interval={end / 2}",
               "--set", f"peridynamics.scatter_seed={seed}"]
        subprocess.run(cmd, check=True)
    series = counts_by_time(os.path.join(out, "fragments.csv"), a.min_mass)
    return {"velocity": v, "cell": cell, "seed": seed, "count_end": series[-1][1],
            "settled": len(series) > 1 and series[-1][1] == series[-2][1], "series": [(t, n) for t, n in series]}


def fit_exponent(vs, ns):
    """Least-squares slope of ln N on ln v."""
    x = [math.log(v) for v in vs]
    y = [math.log(n) for n in ns]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    return sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ballista", default="build/ballista")
    ap.add_argument("--out", required=True)
    ap.add_argument("--velocities", type=float, nargs="+", default=[100, 150, 200, 300, 450, 600])
    ap.add_argument("--cells", type=float, nargs="+", default=[5e-4, 2.5e-4])
    ap.add_argument("--seeds", type=int, default=3, help="draws of the flaws at the coarsest lattice")
    ap.add_argument("--strain", type=float, default=2.0, help="the nominal hoop strain v t / R the runs end at")
    ap.add_argument("--min-mass", type=float, default=1e-4, help="kg: fragments lighter than this are not counted")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--reuse", action="store_true", help="read runs whose summary exists instead of re-running")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    ring = ring_data(DECK)
    rows = []
    coarse = max(a.cells)
    for cell in sorted(a.cells, reverse=True):
        for v in a.velocities:
            for seed in range(a.seeds if cell == coarse else 1):
                rows.append(run(a, v, cell, seed, ring))

    table = []
    for v in a.velocities:
        r = {"velocity": v, "strain_rate": v / ring["R"], "grady": grady_count(ring, v),
             "with_elastic": elastic_energy_count(ring, v)}
        for cell in sorted(a.cells, reverse=True):
            got = [x for x in rows if x["velocity"] == v and x["cell"] == cell]
            ends = [x["count_end"] for x in got]
            r[f"h{cell:g}"] = {"count_end_mean": sum(ends) / len(ends), "count_end": ends}
        table.append(r)
    exponents = {f"h{cell:g}": fit_exponent(a.velocities, [r[f"h{cell:g}"]["count_end_mean"] for r in table])
                 for cell in a.cells}
    # Mott's gamma fitted to the finest lattice's counts: N = 2 pi R eps_dot / sqrt(2 Y / (rho gamma)).
    fine = f"h{min(a.cells):g}"
    gammas = [(r[fine]["count_end_mean"] / (2 * math.pi * ring["R"] * r["strain_rate"])) ** 2
              * 2 * ring["flow_stress"] / ring["density"] for r in table]
    result = {"ring": ring, "min_mass": a.min_mass, "strain": a.strain, "table": table,
              "exponents": exponents, "grady_exponent": 2.0 / 3.0, "mott_exponent": 1.0,
              "mott_gamma_fitted": gammas, "runs": rows}
    with open(os.path.join(a.out, "ring_theory.json"), "w") as f:
        json.dump(result, f, indent=1)

    cells = sorted(a.cells, reverse=True)
    head = ("| v (m/s) | strain rate (1/s) | energy theory N | with the elastic energy | "
            + " | ".join(f"N, {c * 1e3:g} mm lattice" + (f" ({a.seeds} draws)" if c == coarse and a.seeds > 1 else "")
                         for c in cells) + " | finest / energy theory | finest / with the elastic energy |")
    lines = [head, "|" + "---|" * (6 + len(cells))]
    for r in table:
        cols = []
        for c in cells:
            e = r[f"h{c:g}"]["count_end"]
            rising = "" if all(x["settled"] for x in rows if x["velocity"] == r["velocity"] and x["cell"] == c) else "*"
            cols.append(f"{sum(e) / len(e):.1f}{rising}" + (f" ({min(e)}–{max(e)})" if len(e) > 1 else ""))
        ratio = r[fine]["count_end_mean"] / r["grady"]
        ratio_e = r[fine]["count_end_mean"] / r["with_elastic"]
        lines.append(f"| {r['velocity']:g} | {r['strain_rate']:.0f} | {r['grady']:.1f} | {r['with_elastic']:.1f} | "
                     + " | ".join(cols) + f" | {ratio:.2f} | {ratio_e:.2f} |")
    lines.append("")
    lines.append("* a run whose count still grew in its last interval (1/12 of the run).")
    lines.append("")
    lines.append("Exponent p of N = a v^p: " + ", ".join(f"{float(k[1:]) * 1e3:g} mm {p:.2f}"
                                                       for k, p in exponents.items())
                 + " (energy theory 0.67, Mott 1.00); Mott's gamma fitted at the finest lattice: "
                 + ", ".join(f"{g:.0f}" for g in gammas))
    md = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "ring_theory.md"), "w") as f:
        f.write(md)
    print(md)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    fig, ax = plt.subplots(figsize=(5.5, 4))
    vv = [v for v in a.velocities]
    vs = [vv[0] * (vv[-1] / vv[0]) ** (k / 40.0) for k in range(41)]
    ax.plot(vs, [grady_count(ring, v) for v in vs], "k-", label="kinetic energy against G0 (Grady)")
    ax.plot(vs, [elastic_energy_count(ring, v) for v in vs], "k--",
            label="kinetic + elastic energy against G0 (Glenn & Chudnovsky)")
    for c, m in zip(cells, "os^"):
        ax.plot(vv, [r[f"h{c:g}"]["count_end_mean"] for r in table], m, label=f"peridynamics, {c * 1e3:g} mm")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("expansion velocity (m/s)")
    ax.set_ylabel(f"fragments of at least {a.min_mass * 1e3:g} g")
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        axis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xticks([100, 200, 300, 400, 600])
    ax.set_yticks([10, 20, 30, 50, 80])
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "ring_count_velocity.png"), dpi=120)


if __name__ == "__main__":
    main()
