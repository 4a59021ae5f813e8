#!/usr/bin/python3
"""Ballista vs LAMMPS PERI on the disk-indentation problem (issue 12, docs/validation.md).

Runs (unless given existing output) `ballista run examples/pd_disk_indent.yaml` and LAMMPS on
validation/lammps/pd_disk_indent.in (run_lammps_disk.sh, which installs Debian's lammps if
missing), on the same number of cores, then compares at every 100 steps (t = 1e-5 ... 1e-4 s):
kinetic energy, mean and maximum damage, broken bonds and the indenter force, and the throughput
(particle-steps per second) of the two codes measured in this same run.

Usage:
  validation/lammps/compare_disk.py [--threads N] [--ballista BIN] [--out DIR]
                                    [--ballista-out DIR] [--lammps-csv CSV] [--lammps-log LOG]

Exit status 1 if a quantity is outside its tolerance (see TOLERANCES for why each is what it is).

Tolerances. The example deck asks for LAMMPS's conventions where Ballista's defaults differ:
`calibration: continuum` (LAMMPS's c), `contact_pairs: all` (short-range forces on compressed bonds
too) and `break_rule: lammps` (a breaking bond acts once more). The two codes then compute the same
discrete equations, and differ only in summation order (LAMMPS sums over its neighbour lists,
Ballista each bond once from its lower-index end) and in the damage definition (LAMMPS's damage/atom
weighs partners by volume, Ballista by partial volume too: the same broken bonds give a different
mean damage, +17 % at step 100 with the same 18 bonds). Until fracture amplifies the round-off of
the summation order, every number must agree to 1e-4 and the broken-bond count exactly: measured,
the kinetic energy agrees to 9 digits at step 400 and 3e-6 at step 700, the broken bonds are equal
through step 700 (26,112). Brittle cracking then amplifies any difference (a bond that breaks one
step earlier redistributes its load), so from step 800 on the statistics are compared as
statistics: kinetic energy 10 %, indenter force (a noisy contact force) 25 %, broken bonds 35 %.
Mean damage: 35 % throughout (the definitions differ). Maximum damage equal (1) from step 200.
With Ballista's default break_rule (`--set peridynamics.break_rule=work`) the same tolerances do not
hold in the first phase; docs/validation.md shows that comparison too.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# step -> relative tolerance per quantity (see the module docstring).
EARLY = {"ke": 1e-4, "force": 1e-4, "broken": 0.0, "mean_damage": 0.35}  # steps <= EARLY_LAST
LATE = {"ke": 0.10, "force": 0.25, "broken": 0.35, "mean_damage": 0.35}
EARLY_LAST = 700


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def interp(ts, ys, t):
    """The history at time t: the row at t (within a thousandth of LAMMPS's 1e-7 s step: the rows of
    both codes fall every 100 steps), else linear interpolation (if Ballista's step was cut)."""
    near = min(range(len(ts)), key=lambda k: abs(ts[k] - t))
    if abs(ts[near] - t) < 1e-10:
        return ys[near]
    for k in range(1, len(ts)):
        if ts[k] >= t - 1e-15:
            a = (t - ts[k - 1]) / (ts[k] - ts[k - 1]) if ts[k] > ts[k - 1] else 1.0
            return ys[k - 1] + a * (ys[k] - ys[k - 1])
    return ys[-1]


def run_ballista(binary, out, threads):
    cmd = [binary, "run", os.path.join(ROOT, "examples", "pd_disk_indent.yaml"), "-o", out, "--no-plots",
           "--threads", str(threads), "-q"]
    print("[ballista] " + " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def run_lammps(threads, outdir):
    env = dict(os.environ, OUTDIR=outdir)
    cmd = [os.path.join(HERE, "run_lammps_disk.sh"), str(threads), "1000", "100"]
    print("[lammps] " + " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    return os.path.join(outdir, "pd_disk_indent_lammps.csv"), os.path.join(outdir, "log.lammps")


def lammps_throughput(log):
    """Atoms x steps / loop wall time, from LAMMPS's "Loop time of T on P procs for S steps with N atoms"."""
    with open(log) as f:
        m = re.search(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", f.read())
    return None if not m else int(m.group(3)) * int(m.group(2)) / float(m.group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--threads", type=int, default=1, help="Ballista threads = LAMMPS MPI ranks")
    ap.add_argument("--ballista", default=os.path.join(ROOT, "build", "ballista"))
    ap.add_argument("--out", default="/tmp/ballista_disk_compare")
    ap.add_argument("--ballista-out", help="existing Ballista run folder (skip the run)")
    ap.add_argument("--lammps-csv", help="existing LAMMPS CSV of run_lammps_disk.sh (skip the run)")
    ap.add_argument("--lammps-log", help="its log.lammps (for the throughput)")
    a = ap.parse_args()

    bout = a.ballista_out or os.path.join(a.out, "ballista_t%d" % a.threads)
    if not a.ballista_out:
        run_ballista(a.ballista, bout, a.threads)
    if a.lammps_csv:
        lcsv, llog = a.lammps_csv, a.lammps_log
    else:
        lcsv, llog = run_lammps(a.threads, os.path.join(a.out, "lammps_np%d" % a.threads))

    hist = read_csv(os.path.join(bout, "history.csv"))
    t = [float(r["time"]) for r in hist]
    col = lambda name: [float(r[name]) for r in hist]
    ours = {"ke": col("kinetic_energy"), "force": col("indenter_fy"), "broken": col("broken_bonds"),
            "mean_damage": col("mean_damage"), "max_damage": col("max_damage")}
    rows, failures = [], []
    for r in read_csv(lcsv):
        step = int(r["step"])
        if step == 0:
            continue
        ts = float(r["time_s"])
        # LAMMPS's indenter force f_ind[2] is the force ON the indenter from the points (x V): the
        # same sign convention as Ballista's reaction column.
        ref = {"ke": float(r["ke_J"]), "force": float(r["indenter_fy_N"]), "broken": float(r["broken_bonds"]),
               "mean_damage": float(r["damage_mean"]), "max_damage": float(r["damage_max"])}
        tol = EARLY if step <= EARLY_LAST else LATE
        row = {"step": step, "time": ts}
        for q in ("ke", "force", "broken", "mean_damage"):
            b = interp(t, ours[q], ts)
            rel = (b - ref[q]) / ref[q] if ref[q] != 0 else float("inf")
            row[q] = (b, ref[q], rel)
            if abs(rel) > tol[q]:
                failures.append("step %d %s: ballista %.6g vs lammps %.6g (%.1f %% > %.0f %%)" %
                                (step, q, b, ref[q], 100 * rel, 100 * tol[q]))
        bmax = interp(t, ours["max_damage"], ts)
        row["max_damage"] = (bmax, ref["max_damage"], bmax - ref["max_damage"])
        if step > 100 and abs(bmax - ref["max_damage"]) > 1e-12:
            failures.append("step %d max damage: ballista %.6g vs lammps %.6g" % (step, bmax, ref["max_damage"]))
        rows.append(row)

    print("\n| step | KE Ballista (J) | KE LAMMPS (J) | diff | broken B | broken L | diff | mean D B | mean D L | diff |"
          " F_y B (N) | F_y L (N) | diff |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        cells = [str(r["step"])]
        for q in ("ke", "broken", "mean_damage", "force"):
            b, l, rel = r[q]
            cells += ["%.8g" % b, "%.8g" % l, "%+.1e" % rel]
        print("| " + " | ".join(cells) + " |")
    with open(os.path.join(bout, "summary.json")) as f:
        ps_b = json.load(f)["statistics"]["particle_steps_per_second"]
    ps_l = lammps_throughput(llog) if llog else None
    print("\nthroughput on %d core(s): Ballista %.3g particle-steps/s" % (a.threads, ps_b) +
          (", LAMMPS %.3g, ratio %.2f" % (ps_l, ps_b / ps_l) if ps_l else ""))
    if failures:
        print("\nOUTSIDE TOLERANCE:\n  " + "\n  ".join(failures))
        return 1
    print("\nall quantities within tolerance")
    return 0


if __name__ == "__main__":
    sys.exit(main())
