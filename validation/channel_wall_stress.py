#!/usr/bin/python3
"""The stress left in the rock around a penetration channel (thesis seed 000 §6.2, Fig. 6.14): from
the last particle file of an axisymmetric run, the mean radial, hoop and axial stress and the
pressure of the intact rock in rings at increasing distance from the channel's wall, over the
middle of the channel's depth.

  /usr/bin/python3 validation/channel_wall_stress.py RUN_FOLDER [--body 0]

The thesis found "high residual pressures ... along the penetration channel walls" under
confinement, a normal stress that "does not reduce to zero at the cavity's edge" although the
wall is a free surface (or loaded only by the penetrator's debris). A free wall must carry a
radial stress that falls to the debris's pressure there, and rises to the confinement far out
(Lame: sigma_rr = -p_c (1 - a^2 / r^2) around an open hole of radius a in an elastic medium).
"""
import argparse
import glob
import json
import os
import sys

import h5py
import numpy as np

RINGS_MM = [0, 1, 2, 4, 8, 16, 32, 64, 128]  # distance from the wall, mm


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run")
    ap.add_argument("--body", type=int, default=0, help="the rock's body index")
    ap.add_argument("--face", type=float, default=None, help="the struck face's height [m] (default: the run's)")
    a = ap.parse_args()
    last = sorted(glob.glob(os.path.join(a.run, "particles_*.h5")))[-1]
    f = h5py.File(last, "r")
    body = f["body"][:]
    keep = body == a.body
    if "failed" in f:
        keep &= f["failed"][:] == 0  # eroded (comminuted) rock carries no stress: not the wall
    x = f["x"][:][keep]
    x0 = f["x0"][:][keep]
    s = f["stress"][:][keep]
    face = a.face
    if face is None:  # the struck face the run measured its depth from, else the body's top
        summary = os.path.join(a.run, "summary.json")
        face = json.load(open(summary))["penetration"]["surface"] if os.path.exists(summary) else x0[:, 1].max()
    r, depth = x[:, 0], face - x[:, 1]
    # The channel: per 2 mm of depth, the innermost intact particle's radius.
    bins = np.arange(0.0, depth.max(), 2e-3)
    wall = np.full(len(bins), np.nan)
    for k, b in enumerate(bins):
        m = (depth >= b) & (depth < b + 2e-3)
        if m.any():
            wall[k] = r[m].min()
    open_bins = np.where(wall > 1.0e-3)[0]  # a channel at least a cell wide
    if len(open_bins) == 0:
        print("no open channel in", last)
        return 1
    channel_depth = bins[open_bins[-1]] + 2e-3
    lo, hi = 0.25 * channel_depth, 0.75 * channel_depth
    k = np.clip(((depth - 0.0) / 2e-3).astype(int), 0, len(bins) - 1)
    gap = r - wall[k]
    mid = (depth >= lo) & (depth < hi) & np.isfinite(gap)
    print(f"{last}: t = {float(f['time'][()]) * 1e6:.0f} us; channel open to {1000 * channel_depth:.0f} mm, "
          f"wall radius over {1000 * lo:.0f}-{1000 * hi:.0f} mm: {1000 * np.nanmean(wall[(bins >= lo) & (bins < hi)]):.1f} mm")
    print()
    print("| distance from the wall [mm] | particles | sigma_rr [MPa] | sigma_hoop [MPa] | sigma_axial [MPa] | pressure [MPa] |")
    print("|---|---|---|---|---|---|")
    for a0, a1 in zip(RINGS_MM[:-1], RINGS_MM[1:]):
        m = mid & (gap >= a0 * 1e-3) & (gap < a1 * 1e-3)
        if not m.any():
            continue
        rr, zz, tt = s[m, 0].mean(), s[m, 4].mean(), s[m, 8].mean()
        p = -(rr + zz + tt) / 3.0
        print(f"| {a0}-{a1} | {m.sum()} | {rr / 1e6:.1f} | {tt / 1e6:.1f} | {zz / 1e6:.1f} | {p / 1e6:.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
