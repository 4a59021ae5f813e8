#!/usr/bin/python3
"""Fragment trends of a `ballista sweep` of a fragmentation deck (issue 15 item 7: the seed's
sensitivity study of the exploding cylinder to the steel's sound speed and yield stress).

Usage: plot_fragment_sweep.py SWEEP_DIR [--label KEY=NAME ...]

Reads SWEEP_DIR/sweep.csv (docs/sweep.md: one row per run, a column per --vary key path, and the
runs' summary.json scalars, here fragments.count and fragments.mean_mass) and, for each varied
key with at least two values, writes SWEEP_DIR/fragment_sweep_<n>.png: the mean fragment mass and
the fragment count against the varied value (the other keys at the values of the runs plotted:
runs are grouped by the other keys' values, one line per group). It also writes
SWEEP_DIR/fragment_sweep.json: per varied key, whether the mean mass and the count rise or fall
monotonically along it ("rises", "falls" or "mixed"), which is what the seed's conclusions state
(seed 001, "Conclusions from Sensitivity Simulations": with rising sound speed the average mass
falls and the count rises; with rising yield stress the average mass rises and the count falls).
Exit status 0 on success, 2 if the table lacks the columns. Needs matplotlib (BALLISTA_PYTHON).
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend first)


def trend(ys):
    """'rises', 'falls' or 'mixed' along the sequence (strictly)."""
    d = [b - a for a, b in zip(ys, ys[1:])]
    if d and all(x > 0 for x in d):
        return "rises"
    if d and all(x < 0 for x in d):
        return "falls"
    return "mixed"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sweep_dir")
    ap.add_argument("--label", action="append", default=[], help="KEY=NAME: axis label of a varied key")
    a = ap.parse_args()
    path = os.path.join(a.sweep_dir, "sweep.csv")
    if not os.path.exists(path):
        print(f"plot_fragment_sweep: no {path}", file=sys.stderr)
        return 2
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    cols = list(rows[0].keys()) if rows else []
    if "status" not in cols or "fragments.count" not in cols or "fragments.mean_mass" not in cols:
        print("plot_fragment_sweep: sweep.csv lacks status, fragments.count or fragments.mean_mass", file=sys.stderr)
        return 2
    keys = cols[1:cols.index("status")]  # the --vary columns sit between `run` and `status`
    labels = dict(s.split("=", 1) for s in a.label)
    done = [r for r in rows if r["status"] == "completed" and r["fragments.count"] not in ("", None)]
    out = {}
    for n, key in enumerate(keys):
        others = [k for k in keys if k != key]
        groups = {}
        for r in done:
            groups.setdefault(tuple(r[k] for k in others), []).append(r)
        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        result = []
        for g, rs in sorted(groups.items()):
            rs = sorted(rs, key=lambda r: float(r[key]))
            if len(rs) < 2:
                continue
            xs = [float(r[key]) for r in rs]
            mean = [1e3 * float(r["fragments.mean_mass"]) for r in rs]  # g
            count = [float(r["fragments.count"]) for r in rs]
            name = ", ".join(f"{k}={v}" for k, v in zip(others, g)) or "runs"
            ax[0].plot(xs, mean, "o-", label=name)
            ax[1].plot(xs, count, "o-", label=name)
            result.append({"at": dict(zip(others, g)), "values": xs, "mean_mass_g": mean, "count": count,
                           "mean_mass": trend(mean), "count_trend": trend(count)})
        if not result:
            plt.close(fig)
            continue
        for i, what in enumerate(["mean fragment mass [g]", "number of fragments"]):
            ax[i].set_xlabel(labels.get(key, key))
            ax[i].set_ylabel(what)
            ax[i].grid(alpha=0.3)
        ax[0].legend(fontsize=7)
        fig.suptitle(f"Fragments against {labels.get(key, key)}")
        fig.tight_layout()
        fig.savefig(os.path.join(a.sweep_dir, f"fragment_sweep_{n}.png"), dpi=110)
        plt.close(fig)
        out[key] = result
    with open(os.path.join(a.sweep_dir, "fragment_sweep.json"), "w") as f:
        json.dump(out, f, indent=1)
    for key, res in out.items():
        for r in res:
            print(f"{key}: mean fragment mass {r['mean_mass']}, count {r['count_trend']} ({r['values']})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
