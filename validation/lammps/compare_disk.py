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

Tolerances. The two codes solve the same discrete equations (same lattice, bonds, partial volumes,
s0 rule, indenter, contact and step) with three differences: (1) LAMMPS still applies a bond's force
on the step it breaks, Ballista drops it and books its trapezoidal work; (2) LAMMPS's damage/atom
weighs each partner by its volume alone, Ballista by its partial volume too (the seed's V_d/V_0 with
the volume inside the horizon), so the same broken bonds give a different mean damage (+17 % at
step 100 with the same 18 bonds broken); (3) summation order. Before fracture spreads (step 100)
the indenter force, the elastic response of the same bonds to the same indenter, must agree to 2 %
and the broken-bond count to 5 %; the kinetic energy is then tiny (4e-6 J, the disk barely moves
yet) and the breaking rule (1) shows in it: 10 %. Once the disk fractures, brittle cracking
amplifies any difference (a bond that breaks one step earlier redistributes its load and changes
which neighbour breaks next), so the statistics are compared as statistics: kinetic energy (set
by the indenter's push, which both codes apply alike) within 10 %, the indenter force (a noisy
contact force) within 25 %, broken bonds and mean damage (the fracture-sensitive quantities)
within 35 %, maximum damage equal (1, a fully detached point under the indenter).
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
EARLY = {"ke": 0.10, "force": 0.02, "broken": 0.05, "mean_damage": 0.35}
LATE = {"ke": 0.10, "force": 0.25, "broken": 0.35, "mean_damage": 0.35}


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def interp(ts, ys, t):
    """Linear interpolation of the history at time t (Ballista's rows need not fall on t)."""
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
        tol = EARLY if step <= 100 else LATE
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
            cells += ["%.5g" % b, "%.5g" % l, "%+.1f %%" % (100 * rel)]
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
