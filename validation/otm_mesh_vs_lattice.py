#!/usr/bin/python3
"""The OTM quarter Taylor bar from a tetrahedral mesh against the same bar seeded on the lattice.

docs/validation.md, "3D from a tetrahedral mesh": examples/taylor_bar_otm_3d_mesh.yaml with the
bar meshed at cell H (examples/geometry/make_quarter_bar_tets.py --cell H, a point per
tetrahedron, the nodes at its vertices), and the same deck with the analytic cylinder and 2 x 2 x 2
points per lattice cell (--lattice: `cut_lattice`, the surface's sub-cells cut to the cylinder, the
default; or `lattice`, the staircase); grid.cell_size = H and any `--set` for both. The two runs go side by side,
one thread each, with checkpoints every 10 minutes (an interrupted run is resumed by running this
again; `--fresh` starts them anew). Prints the final length and foot radius of each and their difference, then the foot read
from the final particle files in the ways of validation/otm_foot_reading.py (the body's slab radii
against its rim).

  /usr/bin/python3 validation/otm_mesh_vs_lattice.py --ballista build/ballista --cell 0.4 --out out/otm_mesh_lattice
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LATTICE_BODY = ("bodies=[{{name: bar, material: copper, shape: {{type: cylinder, center: [0, 0, 0], axis: y, "
                "radius: 3.2e-3, length: 32.4e-3}}, particles_per_cell: 2, seeding: {}, velocity: [0, -227.0, 0]}}]")


def command(ballista, out, run, cell_mm, overrides):
    folder = os.path.join(out, run)
    base = [ballista, "run"]
    opts = ["-q", "--no-plots", "--threads", "1", "--checkpoint-every-minutes", "10"]
    # A run stopped by a signal writes its checkpoint and a summary with status "interrupted";
    # one killed outright leaves no summary. Either way it goes on from its checkpoints.
    if os.path.isdir(os.path.join(folder, "checkpoints")) and os.listdir(os.path.join(folder, "checkpoints")):
        return base + ["--restart", folder] + opts
    args = base + [os.path.join(out, "deck.yaml"), "-o", folder, "--overwrite"] + opts
    args += ["--set", f"grid.cell_size={cell_mm * 1e-3!r}"]
    for o in overrides:
        args += ["--set", o]
    if run != "mesh":
        args += ["--set", LATTICE_BODY.format(run)]
    return args


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ballista", default=os.path.join(ROOT, "build", "ballista"))
    ap.add_argument("--cell", type=float, required=True, help="cell and element size H, mm")
    ap.add_argument("--out", required=True)
    ap.add_argument("--lattice", choices=["cut_lattice", "lattice"], default="cut_lattice",
                    help="the lattice bar's seeding (default: cut_lattice)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a deck override for both bars (e.g. otm.anti_locking=fbar)")
    ap.add_argument("--result", help="also write the numbers as JSON to this file in --out (ballista validate)")
    ap.add_argument("--fresh", action="store_true",
                    help="start both runs anew (their folders removed), not from earlier runs or checkpoints in --out")
    a = ap.parse_args()
    os.makedirs(os.path.join(a.out, "geometry"), exist_ok=True)
    shutil.copy(os.path.join(ROOT, "examples", "taylor_bar_otm_3d_mesh.yaml"), os.path.join(a.out, "deck.yaml"))
    subprocess.run([sys.executable, os.path.join(ROOT, "examples", "geometry", "make_quarter_bar_tets.py"),
                    "--cell", repr(a.cell), os.path.join(a.out, "geometry", "quarter_bar_tets.exo")], check=True)
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    runs = {}
    pair = ("mesh", a.lattice)
    if a.fresh:
        for run in pair:
            shutil.rmtree(os.path.join(a.out, run), ignore_errors=True)
    for run in pair:
        if os.path.exists(os.path.join(a.out, run, "summary.json")) and \
                json.load(open(os.path.join(a.out, run, "summary.json"))).get("status") == "completed":
            continue
        log = open(os.path.join(a.out, run + ".log"), "w")
        runs[run] = subprocess.Popen(command(a.ballista, a.out, run, a.cell, a.set), stdout=log, stderr=subprocess.STDOUT, env=env)
    for run, p in runs.items():
        if p.wait() != 0:
            print(f"{run}: stopped (see {os.path.join(a.out, run + '.log')})")
    probes = {}
    for run in pair:
        path = os.path.join(a.out, run, "summary.json")
        s = json.load(open(path)) if os.path.exists(path) else {}
        if s.get("status") != "completed":
            print(f"{run}: not completed")
            continue
        probes[run] = s["probes"]
        st = s["statistics"]
        print(f"{run}: {st['particles_seeded']} points, {st['steps']} steps, L_f = {s['probes']['final_length'] * 1e3:.3f} mm, "
              f"R_f = {s['probes']['foot_radius'] * 1e3:.3f} mm, light node-steps {s['solver_results']['light_node_steps']:.0f}")
    result = {"cell_mm": a.cell, "lattice": a.lattice, "overrides": a.set,
              "bars": {run: {k: probes[run][k] for k in ("final_length", "foot_radius")} for run in probes}}
    if len(probes) == 2:
        for key, name in (("final_length", "L_f"), ("foot_radius", "R_f")):
            d = probes["mesh"][key] / probes[a.lattice][key] - 1.0
            result[key + "_difference_pct"] = 100 * d
            print(f"{name}: mesh against {a.lattice} {100 * d:+.2f} %")
    if a.result:
        json.dump(result, open(os.path.join(a.out, a.result), "w"), indent=2)
    if len(probes) == 2:
        subprocess.run([sys.executable, os.path.join(ROOT, "validation", "otm_foot_reading.py")] +
                       [os.path.join(a.out, run) for run in pair], check=True)


if __name__ == "__main__":
    main()
