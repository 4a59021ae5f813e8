#!/usr/bin/python3
"""Checks of tools/plot_penetration.py and tools/plot_sweep_penetration.py (tests/plots/CMakeLists.txt).

Synthetic run folders (the output contract of a run with a `penetration:` section, docs/sweep.md
and tools/plot_penetration.py): depth = U (t - t_s) after a quadratic start-up transient, a
12-segment rod whose segments lose their kinetic energy in turn, a conical channel. Checks:
  full       every file present: the four PNGs are written, are valid PNGs (signature, IHDR, IEND,
             decodable) and are not blank; exit status 0, nothing skipped on stderr
  partial    only history.csv (one segment) and a summary whose penetration values are null: depth
             and energy figures are drawn from history.csv, rate and channel are skipped with a
             note naming them, exit status 0
  unfired    a run stopped in its preparation stage, before the penetrator was fired (every
             penetration_time nan): exit status 0, the depth figure skipped with a note
  empty      no history.csv: non-zero exit and a message naming history.csv, no PNG
  sweep      a sweep_penetration.json of an exact line U = a + bV: both sweep PNGs are valid
  note       the caption's NOT CONVERGED note names its cause: the penetrator's cells across its
             radius, or the refined band ending before the tunnel (summary path_cells); none when
             resolved
"""
import argparse
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import zlib

import numpy as np

U = 2000.0  # steady penetration rate [m/s]
T_S = 2e-6  # transient: depth = U t^2 / (2 T_S) for t < T_S, then U (t - T_S / 2) (C1 continuous)
T_END = 20e-6
N_SEG = 12


def fail(msg):
    sys.exit("FAIL: " + msg)


def depth(t):
    return np.where(t < T_S, U * t * t / (2 * T_S), U * (t - T_S / 2))


def write_csv(path, cols):
    names = list(cols)
    n = len(cols[names[0]])
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for i in range(n):
            f.write(",".join(repr(float(cols[c][i])) for c in names) + "\n")


def write_history(run, n_seg):
    t = np.linspace(-5e-6, T_END, 126)  # negative: overburden stage before firing
    tp = np.clip(t, 0, None)
    d = np.where(t < 0, 0.0, depth(tp))
    seg = {}
    for k in range(n_seg):  # segment k is consumed over [k, k+1] * T_END / n_seg
        frac = np.clip((k + 1) - tp * n_seg / T_END, 0, 1)
        seg[f"segment_kinetic_energy_{k}"] = 1e4 * frac
    total = sum(seg.values())
    cols = {"time": t + 5e-6, "step": np.arange(len(t)), "kinetic_energy": total * 1.5, "penetration_time": t,
            "penetration_depth": d, "cavity_depth": d * 1.02, "penetrator_kinetic_energy": total}
    cols.update(seg)
    write_csv(os.path.join(run, "history.csv"), cols)


def make_full(run):
    os.makedirs(run)
    write_history(run, N_SEG)
    t = np.linspace(0, T_END, 81)
    rate = np.where(t < T_S, U * t / T_S, U)
    write_csv(os.path.join(run, "penetration.csv"),
              {"time": t, "depth": depth(t), "cavity_depth": depth(t) * 1.02, "rate": rate, "cavity_rate": rate * 1.02})
    z = np.linspace(0, depth(np.array(T_END)), 40)
    write_csv(os.path.join(run, "channel.csv"), {"depth": z, "radius": 4e-3 * (1 - z / z[-1]) + 5e-4})
    rho_p, rho_t, V, L = 8960.0, 2200.0, 6000.0, 0.02
    uh = V / (1 + math.sqrt(rho_t / rho_p))  # thesis eq. 3.1
    summary = {"penetration": {
        "impact_velocity": V, "penetrator_density": rho_p, "target_density": rho_t, "penetrator_length": L,
        "segments": N_SEG, "final_depth": float(depth(np.array(T_END))), "final_cavity_depth": 0.0385,
        "stop_time": None, "steady_rate": U,
        "steady_fit": {"intercept": -U * T_S / 2, "t_begin": 2 * T_S, "t_end": T_END, "r2": 1.0},
        "hydrodynamic_rate": uh, "hydrodynamic_depth": L * math.sqrt(rho_p / rho_t), "max_channel_radius": 4.5e-3,
        "analytic": [{"name": "Tate", "depth": 0.03}, {"name": "broken", "depth": None}]}}
    with open(os.path.join(run, "summary.json"), "w") as f:
        json.dump(summary, f)


def make_partial(run):
    os.makedirs(run)
    write_history(run, 1)
    with open(os.path.join(run, "summary.json"), "w") as f:
        json.dump({"error": "stopped early", "penetration": {"steady_rate": None, "steady_fit": None,
                                                             "hydrodynamic_rate": None, "analytic": None}}, f)


def check_png(path):
    """A valid, non-blank PNG: signature, IHDR first with positive size, CRCs, IEND last, decodes."""
    if not os.path.isfile(path):
        fail(f"{path} not written")
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(f"{path}: not a PNG signature")
    pos, chunks = 8, []
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        (crc,) = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])
        if zlib.crc32(kind + body) != crc:
            fail(f"{path}: bad CRC in chunk {kind!r}")
        chunks.append((kind, body))
        pos += 12 + n
    if not chunks or chunks[0][0] != b"IHDR" or chunks[-1][0] != b"IEND":
        fail(f"{path}: chunks must start with IHDR and end with IEND, got {[c[0] for c in chunks]}")
    w, h = struct.unpack(">II", chunks[0][1][:8])
    if w < 100 or h < 100:
        fail(f"{path}: {w} x {h} pixels")
    import matplotlib.image as mpimg
    img = mpimg.imread(path)
    if float(np.std(img[..., :3])) < 0.01:  # a figure with axes, labels and curves is far from uniform
        fail(f"{path}: blank image")


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
    return p.returncode, p.stderr


FIGS = ["penetration_depth.png", "penetration_rate.png", "penetrator_energy.png", "channel_profile.png"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tools", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    py, plot = sys.executable, os.path.join(a.tools, "plot_penetration.py")

    full = os.path.join(a.out, "full")
    make_full(full)
    rc, err = run([py, plot, full])
    if rc != 0:
        fail(f"full run folder: exit {rc}: {err}")
    if "skipped" in err:
        fail(f"full run folder: a figure was skipped: {err}")
    for name in FIGS:
        check_png(os.path.join(full, name))

    partial = os.path.join(a.out, "partial")
    make_partial(partial)
    rc, err = run([py, plot, partial])
    if rc != 0:
        fail(f"partial run folder must still succeed, exit {rc}: {err}")
    for name in ["penetration_depth.png", "penetrator_energy.png"]:
        check_png(os.path.join(partial, name))
    for name in ["penetration_rate.png", "channel_profile.png"]:
        if os.path.exists(os.path.join(partial, name)):
            fail(f"partial: {name} drawn without its data")
        if f"{name} skipped" not in err:
            fail(f"partial: no note that {name} was skipped in stderr: {err!r}")

    unfired = os.path.join(a.out, "unfired")
    os.makedirs(unfired)
    t = np.linspace(0, 5e-6, 11)
    write_csv(os.path.join(unfired, "history.csv"), {
        "time": t, "step": np.arange(len(t)), "kinetic_energy": 1e-3 * t, "penetration_time": np.full(len(t), np.nan),
        "penetration_depth": np.zeros(len(t)), "cavity_depth": np.zeros(len(t)),
        "penetrator_kinetic_energy": np.zeros(len(t))})
    with open(os.path.join(unfired, "summary.json"), "w") as f:
        json.dump({"status": "interrupted", "penetration": {"steady_rate": None, "steady_fit": None,
                                                            "hydrodynamic_rate": 2000.0, "analytic": None}}, f)
    rc, err = run([py, plot, unfired])
    if rc != 0:
        fail(f"a run stopped before firing must still succeed, exit {rc}: {err}")
    if "penetration_depth.png skipped" not in err or os.path.exists(os.path.join(unfired, "penetration_depth.png")):
        fail(f"unfired: the depth figure must be skipped with a note: {err!r}")

    empty = os.path.join(a.out, "empty")
    os.makedirs(empty)
    rc, err = run([py, plot, empty])
    if rc == 0:
        fail("no history.csv: exit status 0")
    if "history.csv" not in err:
        fail(f"no history.csv: the message does not name history.csv: {err!r}")
    if any(f.endswith(".png") for f in os.listdir(empty)):
        fail("no history.csv: a PNG was written")

    sys.path.insert(0, a.tools)
    import plot_penetration  # noqa: E402
    note = plot_penetration.convergence_note
    thin = note({"resolved": False, "cells_across_radius": 1.0, "path_cells": {"coarser_from_depth": None}})
    if "1 cells across its radius" not in thin:
        fail(f"note of a thin penetrator: {thin!r}")
    past = note({"resolved": False, "cells_across_radius": 4.0, "path_cells": {"coarser_from_depth": 0.13}})
    if "ends 130.0 mm deep" not in past or "across its radius" in past:
        fail(f"note of a tunnel beyond the band: {past!r}")
    if note({"resolved": True, "cells_across_radius": 4.0}) != "":
        fail("a resolved run has a NOT CONVERGED note")

    sweep = os.path.join(a.out, "sweep")
    os.makedirs(sweep)
    rho_p, rho_t, aa, bb = 8960.0, 2200.0, 600.0, 0.55
    runs = []
    for k, V in enumerate([1000.0, 2000.0, 3000.0, 4000.0]):
        uh = V / (1 + math.sqrt(rho_t / rho_p))
        runs.append({"run": k, "V": V, "U": aa + bb * V, "U_h": uh, "U_over_Uh": (aa + bb * V) / uh, "R_minus_Y": None})
    with open(os.path.join(sweep, "sweep_penetration.json"), "w") as f:
        json.dump({"a": aa, "b": bb, "r2": 1.0, "penetrator_density": rho_p, "target_density": rho_t,
                   "curvature": None, "extremum_velocity": None, "runs": runs}, f)
    rc, err = run([py, os.path.join(a.tools, "plot_sweep_penetration.py"), sweep])
    if rc != 0:
        fail(f"sweep plots: exit {rc}: {err}")
    for name in ["penetration_u_vs_v.png", "penetration_u_over_uh.png"]:
        check_png(os.path.join(sweep, name))
    rc, err = run([py, os.path.join(a.tools, "plot_sweep_penetration.py"), empty])
    if rc == 0 or "sweep_penetration.json" not in err:
        fail(f"sweep plots without sweep_penetration.json: exit {rc}, {err!r}")
    print("plots: all checks passed")


if __name__ == "__main__":
    main()
