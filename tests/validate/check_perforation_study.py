#!/usr/bin/python3
"""validation/perforation_convergence.py's arithmetic on inputs with known answers.

- Where the spent jet lies: a run folder written by hand (resolved.yaml and one particle output) in
  which a jet flying along -y onto a face at y = 0.2 m has a known share of its mass within 10 mm of
  the cavity's bottom (points placed 9.9 and 10.1 mm from it on either side, and far away; a
  target body present so that the penetrator must be picked by name). The share is a ratio of
  sums of exactly representable masses: exact to round-off. A jet flying along +y is refused (the
  depth is measured along -y), not read as garbage.
- The depth to which the tunnel is as wide as the jet's tip: a run folder written by hand whose
  intact rock reaches r < 1 mm (the tip radius its resolved.yaml states) first at 160 mm, with a
  hole 0.05 mm wide on the axis beyond it to 170 mm and failed debris at 100 mm inside the tunnel;
  every point's half-extent along the flight is |F_yx| h_x + |F_yy| h_y = 0.1 mm. The depth is
  159.9 mm at the tip radius and 169.9 mm at 0.1 mm, the debris not counted: sums of exactly
  representable numbers, to 1e-12 m.
- Richardson: f(h) = f0 + c h^2 at h, h/2, h/4 gives the observed order 2 and the estimate f0 to
  round-off (Roache 1998, ch. 5); differences that grow give no estimate; a non-monotone sequence
  gives no order.
- Oscillating levels (10, 12, 11): half the range over the finest, 1/11; monotone ones: none.
- A hole's diameters averaged per millimetre of the layer: slices of 0.25 mm through 2 mm, one
  millimetre with a slice gone (averaged over the rest) and one with none (None): exact sums.
- A level is done only when its summary says "completed": a run stopped by a signal writes
  summary.json too (status "interrupted"), and `--reuse` must not take it for an answer nor
  `--resume` skip it."""
import json
import os
import sys
import types

import h5py
import numpy as np

import script_args

SURFACE, CAVITY = 0.2, 0.150


def write_run(run_dir, direction):
    os.makedirs(run_dir, exist_ok=True)
    open(os.path.join(run_dir, "resolved.yaml"), "w").write(
        "bodies:\n"
        "  - name: rock\n    material: rock\n"
        f"  - name: jet\n    material: copper\n    jet: {{axis: y, direction: {direction}}}\n")
    # depth below the face -> (mass, count); within 10 mm of CAVITY: 0.1402-0.1599 m
    jet = [(CAVITY - 0.0099, 2.0, 3), (CAVITY + 0.0099, 1.0, 2), (CAVITY, 0.5, 4),  # near: 6 + 2 + 2 = 10
           (CAVITY - 0.0101, 4.0, 5), (CAVITY + 0.0101, 1.0, 6), (0.030, 0.25, 16)]  # far: 20 + 6 + 4 = 30
    depth = np.concatenate([np.full(n, d) for d, _, n in jet])
    mass = np.concatenate([np.full(n, m) for _, m, n in jet])
    rock_depth = np.linspace(0.0, 0.2, 50)
    x = np.zeros((depth.size + rock_depth.size, 3))
    x[:, 1] = SURFACE - np.r_[rock_depth, depth]
    x[:, 0] = 1.0e-3
    with h5py.File(os.path.join(run_dir, "particles_000000.h5"), "w") as f:
        f.attrs["body_names"] = '["rock", "jet"]'
        f["x"] = x
        f["body"] = np.r_[np.zeros(rock_depth.size, dtype=np.int32), np.ones(depth.size, dtype=np.int32)]
        f["mass"] = np.r_[np.full(rock_depth.size, 100.0), mass]  # heavy rock: counted as jet, it shows
        f["segment"] = np.r_[np.full(rock_depth.size, -1), np.zeros(depth.size, dtype=np.int32)]
        f["failed"] = np.zeros(depth.size + rock_depth.size, dtype=np.int32)
        f["time"] = 1.0e-4


def write_tunnel(run_dir):
    """Rock whose tunnel narrows below the jet's 1 mm tip radius at 160 mm, a 0.05 mm hole on the
    axis to 170 mm, failed debris at 100 mm on the axis; one jet point."""
    os.makedirs(run_dir, exist_ok=True)
    open(os.path.join(run_dir, "resolved.yaml"), "w").write(
        "bodies:\n"
        "  - name: rock\n    material: rock\n"
        "  - name: jet\n    material: copper\n"
        "    jet: {axis: y, direction: -1, segments: [[1.0e-3, 6.0e-3, 7000, 0]]}\n")
    depths = np.linspace(0.0, 0.2, 401)
    rock = [(d, 3.0e-3, 0) for d in depths]                     # the tunnel's wall, r = 3 mm
    rock += [(d, 0.5e-3, 0) for d in depths if d >= 0.160]      # it narrows below 1 mm at 160 mm
    rock += [(d, 0.05e-3, 0) for d in depths if d >= 0.170]     # the axis is rock again at 170 mm
    rock += [(0.100, 0.02e-3, 1), (0.100, 0.5e-3, 1)]           # failed debris: not the floor
    n = len(rock) + 1
    x = np.zeros((n, 3))
    x[:-1, 0] = [r for _, r, _ in rock]
    x[:-1, 1] = [SURFACE - d for d, _, _ in rock]
    x[-1] = [0.0, SURFACE - 0.150, 0.0]
    F = np.tile([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], (n, 1))
    F[::2, 3] = -0.5       # a sheared point: F_yx h_x + F_yy h_y = 0.5 * 0.04 + 1 * 0.08 = 0.1 mm
    half = np.tile([0.0e-3, 0.1e-3, 0.0], (n, 1))
    half[::2] = [0.04e-3, 0.08e-3, 0.0]
    with h5py.File(os.path.join(run_dir, "particles_000000.h5"), "w") as f:
        f.attrs["body_names"] = '["rock", "jet"]'
        f["x"] = x
        f["body"] = np.r_[np.zeros(n - 1, dtype=np.int32), [1]]
        f["mass"] = np.ones(n)
        f["segment"] = np.r_[np.full(n - 1, -1), [0]]
        f["failed"] = np.r_[[fl for _, _, fl in rock], [0]].astype(np.int32)
        f["F"] = F
        f["half_size"] = half
        f["time"] = 1.0e-4


def main():
    a = script_args.parse()
    from perforation_convergence import (final_points, jet_at_bottom, level_done, level_sets, oscillation, per_mm,
                                         richardson, tunnel_depth)
    pen = {"penetrator": "jet", "target": "rock", "surface": SURFACE}
    failures = 0

    # The far-field level is the uniform grid even when the deck ships refined bands of its own (the
    # demo does): it must clear them, or it runs the deck's bands and is not the coarsest level.
    far, fine = level_sets(1e-3, 1e-3, 9e-3, [0.03, 0.135]), level_sets(0.5e-3, 1e-3, 9e-3, [0.03, 0.135])
    plain = ["grid.patches=[]", "mpm.multirate=none"]  # the deck's patches and step per region are no level
    ok = (far == ["grid.cell_size=0.001", "grid.refine=[]"] + plain and fine[0] == "grid.cell_size=0.001"
          and "cell_size: 0.0005" in fine[1] and "from: 0.03, to: 0.135" in fine[1] and fine[2:] == plain)
    print(f"far-field level clears the deck's bands, patches and step per region {far}, a finer one sets the "
          f"bands: {'ok' if ok else 'FAIL'}")
    failures += not ok

    run_dir = os.path.join(a.out, "jet_down")
    write_run(run_dir, -1)
    share = jet_at_bottom(final_points(run_dir, pen), CAVITY)
    ok = share is not None and abs(share - 0.25) < 1e-12
    print(f"jet within 10 mm of the cavity's bottom: {share} (exact 0.25): {'ok' if ok else 'FAIL'}")
    failures += not ok

    run_dir = os.path.join(a.out, "jet_up")
    write_run(run_dir, 1)
    refused = final_points(run_dir, pen) is None
    print(f"a jet flying along +y refused: {'ok' if refused else 'FAIL'}")
    failures += not refused

    run_dir = os.path.join(a.out, "tunnel")
    write_tunnel(run_dir)
    points = final_points(run_dir, pen)
    tip = points["tip_radius"]
    at_tip, at_hole = tunnel_depth(points, tip), tunnel_depth(points, 0.1e-3)
    ok = (tip == 1.0e-3 and abs(at_tip - 0.1599) < 1e-12 and abs(at_hole - 0.1699) < 1e-12)
    print(f"tunnel depth at the tip radius {tip}: {at_tip} (exact 0.1599), at 0.1 mm: {at_hole} (exact 0.1699): "
          f"{'ok' if ok else 'FAIL'}")
    failures += not ok

    f0, c, h = 150.0, 40.0, 1.0
    p, est = richardson(*(f0 + c * (h / 2 ** k) ** 2 for k in range(3)))
    ok = abs(p - 2.0) < 1e-12 and abs(est - f0) < 1e-12 * f0
    print(f"Richardson on f0 + c h^2: order {p}, estimate {est} (exact 2, {f0}): {'ok' if ok else 'FAIL'}")
    failures += not ok
    p, est = richardson(123.0, 153.0, 185.0)  # differences 30 and 32: they grow
    ok = p is not None and p < 0 and est is None
    print(f"growing differences: order {p}, no estimate: {'ok' if ok else 'FAIL'}")
    failures += not ok
    p, est = richardson(10.0, 12.0, 11.0)
    ok = p is None and est is None
    print(f"not monotone: no order: {'ok' if ok else 'FAIL'}")
    failures += not ok
    osc, mono = oscillation(10.0, 12.0, 11.0), oscillation(123.0, 153.0, 185.0)
    ok = osc is not None and abs(osc - 1.0 / 11.0) < 1e-15 and mono is None
    print(f"oscillating levels: half range {osc} (exact 1/11), monotone: {mono}: {'ok' if ok else 'FAIL'}")
    failures += not ok
    d = [0.010, 0.012, None, 0.014, None, None, None, None]
    prof = per_mm({"diameters": d, "thickness": 0.002})
    ok = len(prof) == 2 and abs(prof[0] - 12.0) < 1e-12 and prof[1] is None
    print(f"hole per millimetre: {prof} (exact [12.0, None]): {'ok' if ok else 'FAIL'}")
    failures += not ok
    states = {}
    for status in ("completed", "interrupted", "failed", None):
        level = os.path.join(a.out, f"level_{status}")
        os.makedirs(level, exist_ok=True)
        summary = os.path.join(level, "summary.json")
        if status is None:
            if os.path.exists(summary):
                os.remove(summary)
        else:
            open(summary, "w").write(json.dumps({"status": status}))
        states[status] = level_done(level)
    ok = states == {"completed": True, "interrupted": False, "failed": False, None: False}
    print(f"a level is done only when completed: {states}: {'ok' if ok else 'FAIL'}")
    failures += not ok
    # --resume keeps a completed level: the run is not started again (a ballista that fails at
    # once would stop the study).
    from perforation_convergence import run_level
    study = os.path.join(a.out, "resumed_study")
    os.makedirs(os.path.join(study, "h_1mm", "checkpoints"), exist_ok=True)
    open(os.path.join(study, "h_1mm", "checkpoints", "checkpoint_000000000010.h5"), "w").write("")
    open(os.path.join(study, "h_1mm", "summary.json"), "w").write(json.dumps({"status": "completed", "depth": 1}))
    args = types.SimpleNamespace(out=study, reuse=False, resume=True, ballista="/bin/false", threads=1,
                                 deck="unused.yaml", far=1e-3, band=9e-3, path=[0.0, 0.1], set=[])
    try:
        kept, wall = run_level(args, 1e-3)
        ok = kept.get("depth") == 1 and wall is None
    except SystemExit:
        ok = False
    print(f"--resume keeps a completed level: {'ok' if ok else 'FAIL'}")
    failures += not ok
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
