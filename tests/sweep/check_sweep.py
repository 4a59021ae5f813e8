#!/usr/bin/env python3
"""End-to-end check of `ballista sweep` (tests/sweep/CMakeLists.txt)."""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys

# Reduced size: coarse cells and a short end time (the disks meet at t ~ 1 s at the slowest speed).
REDUCED = ["--set", "grid.cell_size=0.05", "--set", "simulation.end_time=0.5"]
VELOCITIES = ["[0.05,0.05,0]", "[0.1,0.1,0]", "[0.2,0.2,0]"]
MODULI = ["1000", "2000"]
V_OTHER = (-0.1, -0.1)  # the upper-right disk's velocity in the deck


def fail(msg):
    sys.exit("FAIL: " + msg)


def run(cmd, expect):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != expect:
        fail(f"{' '.join(cmd)} exited {p.returncode}, expected {expect}:\n{p.stdout}\n{p.stderr}")
    # make test-sanitize: a UBSan abort exits non-zero too (ASan reports go to files there).
    if "runtime error:" in p.stderr:
        fail(f"{' '.join(cmd)}: UndefinedBehaviorSanitizer report:\n{p.stderr}")
    return p


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [dict(zip(rows[0], r)) for r in rows[1:]]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ballista", required=True)
    ap.add_argument("--deck", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    b, deck = a.ballista, a.deck

    # 1. Two axes, 3 x 2 = 6 runs, two at a time.
    out = os.path.join(a.out, "ok")
    run([b, "sweep", deck, "--vary", "bodies.0.velocity=" + ",".join(VELOCITIES), "--vary",
         "materials.soft.youngs_modulus=" + ",".join(MODULI), "--jobs", "2", "-o", out, "-q"] + REDUCED, 0)
    cols, rows = read_csv(os.path.join(out, "sweep.csv"))
    if cols[:5] != ["run", "bodies.0.velocity", "materials.soft.youngs_modulus", "status", "error"]:
        fail(f"leading columns {cols[:5]}")
    for c in ["probes.kinetic_energy", "probes.strain_energy", "energy.initial_total", "energy.total", "energy.mass",
              "statistics.steps", "statistics.wall_time", "statistics.threads"]:
        if c not in cols:
            fail(f"column {c} missing from sweep.csv: {cols}")
    if len(rows) != 6:
        fail(f"{len(rows)} rows, expected 6")
    threads = str(max(1, (os.cpu_count() or 1) // 2))  # max(1, cores / jobs)
    for k, r in enumerate(rows):
        v, E = VELOCITIES[k // 2], MODULI[k % 2]  # the last --vary varies fastest
        if (r["run"], r["bodies.0.velocity"], r["materials.soft.youngs_modulus"]) != (str(k), v, E):
            fail(f"row {k} is {r}")
        if r["status"] != "completed" or r["error"]:
            fail(f"run {k}: {r['status']} {r['error']}")
        if r["statistics.threads"] != threads:
            fail(f"run {k} ran on {r['statistics.threads']} threads, expected {threads}")
        if not os.path.exists(os.path.join(out, f"run_{k}", "summary.json")):
            fail(f"run_{k}/summary.json missing")
        # Both disks are the same seeded shape, so each carries half the mass: the initial kinetic
        # energy is m/4 (|v_a|^2 + |v_b|^2) up to summation round-off (1e-9 relative).
        va = [float(x) for x in v.strip("[]").split(",")]
        m = float(r["energy.mass"])
        ke0 = 0.25 * m * (va[0] ** 2 + va[1] ** 2 + V_OTHER[0] ** 2 + V_OTHER[1] ** 2)
        e0 = float(r["energy.initial_total"])
        if abs(e0 - ke0) > 1e-9 * ke0:
            fail(f"run {k}: initial energy {e0}, expected m/4 (|va|^2 + |vb|^2) = {ke0}")
        # FLIP with an elastic material conserves energy; the example deck asserts < 1 % drift.
        if abs(float(r["energy.total"]) - e0) > 0.01 * e0:
            fail(f"run {k}: energy {r['energy.total']} drifted from {e0} by more than 1 %")
    # Larger impact velocity -> larger kinetic energy at the end, at either modulus.
    for j in range(2):
        ke = [float(rows[i * 2 + j]["probes.kinetic_energy"]) for i in range(3)]
        if not ke[0] < ke[1] < ke[2]:
            fail(f"kinetic energy not increasing with velocity at E = {MODULI[j]}: {ke}")
    js = json.load(open(os.path.join(out, "sweep.json")))
    if js["columns"] != cols or len(js["runs"]) != 6 or js["axes"][1]["values"] != MODULI:
        fail("sweep.json does not match sweep.csv")
    if js["runs"][3]["materials.soft.youngs_modulus"] != 2000 or js["runs"][3]["probes.kinetic_energy"] != float(
            rows[3]["probes.kinetic_energy"]):
        fail(f"sweep.json run 3: {js['runs'][3]}")

    # 2. A run that fails (the disks leave the grid) is recorded; the others still run; exit 3.
    out = os.path.join(a.out, "failing")
    p = run([b, "sweep", deck, "--vary", "bodies.0.velocity=[60,60,0],[0.1,0.1,0]", "--jobs", "2", "-o", out] +
            REDUCED, 3)
    if "run_0" not in p.stderr or "left the grid" not in p.stderr:
        fail(f"failed run not reported: {p.stderr}")
    cols, rows = read_csv(os.path.join(out, "sweep.csv"))
    if [r["status"] for r in rows] != ["failed", "completed"]:
        fail(f"statuses {[r['status'] for r in rows]}")
    if "left the grid" not in rows[0]["error"] or not rows[0]["failed_step"] or rows[1]["failed_step"] != "":
        fail(f"failed row {rows[0]}, completed row failed_step '{rows[1].get('failed_step')}'")

    # 3. Bad options name themselves; nothing runs.
    out = os.path.join(a.out, "bad")
    p = run([b, "sweep", deck, "--vary", "simulation.cfl=0.1", "--vary", "simulation.cfll=0.1,0.2", "-o", out], 2)
    if "run 0" not in p.stderr or "simulation.cfll" not in p.stderr or "did you mean 'cfl'" not in p.stderr:
        fail(f"unknown key not named: {p.stderr}")
    p = run([b, "sweep", deck, "--vary", "simulation.cfl=", "-o", out], 1)
    if "--vary 'simulation.cfl=': empty value list" not in p.stderr:
        fail(f"empty list not named: {p.stderr}")
    p = run([b, "sweep", deck, "--vary", "simulation.cfl", "-o", out], 1)
    if "--vary 'simulation.cfl': no '='" not in p.stderr:
        fail(f"malformed --vary not named: {p.stderr}")
    if os.path.exists(out):
        fail("a rejected sweep created its folder")
    print("sweep: all checks passed")


if __name__ == "__main__":
    main()
