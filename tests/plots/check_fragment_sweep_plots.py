#!/usr/bin/python3
"""tools/plot_fragment_sweep.py on a synthetic sweep folder (issue 15 item 7): a 3 x 2 sweep of
two keys whose fragment means and counts are made to rise or fall along each key, so that the
trends the tool reports are known; the figures must be valid non-blank PNGs; a table without the
fragment columns is rejected with status 2."""
import argparse
import csv
import json
import os
import subprocess
import sys


def png_ok(path):
    with open(path, "rb") as f:
        head = f.read(8)
    return head == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 5000


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tools", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    tool = os.path.join(a.tools, "plot_fragment_sweep.py")
    rows = []
    k = 0
    for c in (0.65, 1.0, 1.35):  # sound speed factor: mass falls, count rises
        for y in (375e6, 750e6):  # yield stress: mass rises, count falls (one failed run below)
            rows.append({"run": k, "c": c, "y": y, "status": "completed", "error": "",
                         "fragments.count": 200 + 100 * c - y / 1e7, "fragments.mean_mass": 1e-3 * (2 - c) * y / 375e6})
            k += 1
    rows.append({"run": k, "c": 2.0, "y": 375e6, "status": "failed", "error": "x", "fragments.count": "",
                 "fragments.mean_mass": ""})
    with open(os.path.join(a.out, "sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    r = subprocess.run([sys.executable, tool, a.out, "--label", "c=sound speed factor"], capture_output=True, text=True)
    fails = []
    if r.returncode != 0:
        fails.append(f"status {r.returncode}: {r.stderr}")
    res = json.load(open(os.path.join(a.out, "fragment_sweep.json")))
    for g in res["c"]:
        if (g["mean_mass"], g["count_trend"]) != ("falls", "rises"):
            fails.append(f"c: {g}")
        if g["values"] != [0.65, 1.0, 1.35]:  # the failed run is left out
            fails.append(f"c values {g['values']}")
    for g in res["y"]:
        if (g["mean_mass"], g["count_trend"]) != ("rises", "falls"):
            fails.append(f"y: {g}")
    if len(res["c"]) != 2 or len(res["y"]) != 3:
        fails.append("groups: one line per value of the other key")
    for n in (0, 1):
        p = os.path.join(a.out, f"fragment_sweep_{n}.png")
        if not (os.path.exists(p) and png_ok(p)):
            fails.append(f"{p} missing or blank")
    bad = os.path.join(a.out, "bad")
    os.makedirs(bad, exist_ok=True)
    with open(os.path.join(bad, "sweep.csv"), "w") as f:
        f.write("run,c,status,error\n0,1,completed,\n")
    r = subprocess.run([sys.executable, tool, bad], capture_output=True, text=True)
    if r.returncode != 2:
        fails.append(f"a table without fragment columns: status {r.returncode}")
    for m in fails:
        print("FAIL:", m)
    print("ok" if not fails else f"{len(fails)} failure(s)")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
