#!/usr/bin/env python3
"""Run every example at its CI size with two ballista builds and compare the results bitwise.

Results a change does not mean to alter must stay bitwise (docs/architecture.md): this runs each
examples/*.yaml (not drive_*) with the reduced-size --set overrides of tests/examples/CMakeLists.txt,
once with --base and once with --new, and compares
  - every dataset of every particle file (particles_*.h5), array by array, byte for byte;
  - history.csv and the other CSVs (penetration, channel, fragments), byte for byte;
  - summary.json, less what differs between any two runs (wall time, rates, timing, paths, the
    build's commit):
    values present in both must be equal; keys only one build writes are listed, not failed.
Exit status 1 if anything differs. Uses Debian's h5py (/usr/bin/python3).

  /usr/bin/python3 tools/compare_builds.py --base /tmp/base/ballista --new build/ballista --out /tmp/cmp
  ... --base-source /tmp/base     # a change that edits an example: the base runs its own deck
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VOLATILE = {"wall_time", "particle_steps_per_second", "timing", "deck", "restarted_from", "threads", "build"}


def ci_overrides(repo=REPO):
    """{stem: [--set values]} from tests/examples/CMakeLists.txt of `repo`."""
    text = open(os.path.join(repo, "tests", "examples", "CMakeLists.txt")).read()
    out = {}
    for m in re.finditer(r"set\(example_set_(\w+)((?:\s+\"[^\"]*\")+)\s*\)", text, re.S):
        out[m.group(1)] = re.findall(r"\"([^\"]*)\"", m.group(2))
    return out


def run(binary, deck, out, sets):
    shutil.rmtree(out, ignore_errors=True)  # a fresh folder: builds before the run-folder lock take no --overwrite
    cmd = [binary, "run", deck, "-o", out, "-q", "--no-plots", "--threads", "2"]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode, p.stdout[-2000:]


def flat(node, prefix=""):
    if isinstance(node, dict):
        res = {}
        for k, v in node.items():
            if k in VOLATILE:
                continue
            res.update(flat(v, prefix + k + "."))
        return res
    return {prefix.rstrip("."): json.dumps(node, sort_keys=True)}


def compare_h5(a, b):
    bad = []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names_a, names_b = set(), set()
        fa.visititems(lambda n, o: names_a.add(n) if isinstance(o, h5py.Dataset) else None)
        fb.visititems(lambda n, o: names_b.add(n) if isinstance(o, h5py.Dataset) else None)
        if names_a != names_b:
            bad.append(f"datasets differ: only base {sorted(names_a - names_b)}, only new {sorted(names_b - names_a)}")
        for n in sorted(names_a & names_b):
            x, y = np.asarray(fa[n]), np.asarray(fb[n])
            if x.shape != y.shape or x.dtype != y.dtype or x.tobytes() != y.tobytes():
                bad.append(f"dataset {n} differs")
    return bad


def compare(base_dir, new_dir):
    bad, notes = [], []
    files = sorted(set(os.listdir(base_dir)) | set(os.listdir(new_dir)))
    for f in files:
        a, b = os.path.join(base_dir, f), os.path.join(new_dir, f)
        if f.startswith(".") or os.path.isdir(a) or os.path.isdir(b) or f.endswith((".png", ".yaml", ".xdmf")):
            continue
        if not (os.path.exists(a) and os.path.exists(b)):
            bad.append(f"{f} only in {'base' if os.path.exists(a) else 'new'}")
        elif f.endswith(".h5"):
            bad += [f"{f}: {x}" for x in compare_h5(a, b)]
        elif f == "summary.json":
            sa, sb = flat(json.load(open(a))), flat(json.load(open(b)))
            for k in sorted(set(sa) & set(sb)):
                if sa[k] != sb[k]:
                    bad.append(f"summary.json {k}: {sa[k]} != {sb[k]}")
            only = sorted(set(sa) ^ set(sb))
            if only:
                notes.append("summary.json keys in one build only: " + ", ".join(only[:12]))
        elif open(a, "rb").read() != open(b, "rb").read():
            bad.append(f"{f} differs")
    return bad, notes


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--base", required=True, help="ballista of the base commit")
    ap.add_argument("--new", required=True, help="ballista of the change")
    ap.add_argument("--out", required=True, help="folder for both runs of every example")
    ap.add_argument("--only", action="append", default=[], help="example stem (repeatable)")
    ap.add_argument("--base-source", default=REPO,
                    help="checkout of the base commit: the base runs its examples and CI sizes (for a change "
                         "that edits a deck, or its CI size, without meaning to change the results there)")
    a = ap.parse_args()
    sets = ci_overrides()
    base_sets = ci_overrides(a.base_source)
    decks = sorted(f for f in os.listdir(os.path.join(REPO, "examples"))
                   if f.endswith(".yaml") and not f.startswith("drive_"))
    failed = 0
    for d in decks:
        stem = d[:-5]
        if a.only and stem not in a.only:
            continue
        base_deck = os.path.join(a.base_source, "examples", d)
        if not os.path.isfile(base_deck):
            print(f"{stem}: new (not in the base)")
            continue
        results = []
        for which, binary, deck, s in (("base", a.base, base_deck, base_sets), ("new", a.new,
                                        os.path.join(REPO, "examples", d), sets)):
            out = os.path.join(a.out, stem, which)
            results.append((out,) + run(binary, deck, out, s.get(stem, [])))
        (ob, cb, lb), (on, cn, ln) = results
        if cb != cn:
            print(f"{stem}: exit {cb} (base) != {cn} (new)\n  base: {lb[-300:]}\n  new: {ln[-300:]}")
            failed += 1
            continue
        bad, notes = compare(ob, on)
        print(f"{stem}: " + ("bitwise identical" if not bad else "DIFFERS") + (f" (exit {cb})" if cb else ""))
        for x in bad[:10] + notes:
            print("  " + x)
        failed += bool(bad)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
