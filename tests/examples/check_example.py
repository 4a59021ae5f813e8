#!/usr/bin/env python3
"""Smoke checks of the shipped example decks (tests/examples/CMakeLists.txt).

Two modes:

  check_example.py run --ballista BIN --deck DECK --out DIR [--set K=V ...] [--probe NAME ...]
      Runs `BIN run DECK -o DIR -q --set ...` and checks its outputs:
        * exit status 0 and summary.json with status "completed";
        * history.csv with a header, at least two rows, every value finite, and the probes as
          columns;
        * particles.xdmf parses as XML, every .h5 file it references exists, opens with h5py and
          holds the referenced dataset with the advertised dimensions; the final output's time
          equals the summary's end time;
        * every deck probe and every --probe NAME is in summary.json and finite.

  check_example.py drive --ballista BIN --deck DECK --out DIR [--set K=V ...]
      Runs `BIN drive DECK -o DIR -q --set ...` (single-element driver) and checks: exit status 0,
      summary.json with status "completed", resolved.yaml, and history.csv with the driver's columns
      (step, t, F11..F33, sigma_*, sigma_bar_*, I1, sqrt_J2, pressure), at least two rows, every
      value finite, times increasing, and as many rows as summary.json's statistics.records.

  check_example.py typo --ballista BIN --deck DECK --out DIR --key KEY --typo TYPO
      Copies DECK to DIR with the first `KEY:` misspelt as `TYPO:`, runs `BIN run` on it and
      checks that it exits non-zero without creating a results folder and that stderr names the
      deck file, the line and column of the typo, the misspelt key and the suggested key.

Needs numpy and h5py (BALLISTA_PYTHON, /usr/bin/python3).
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET


def fail(msg):
    print("FAIL: " + msg, file=sys.stderr)
    sys.exit(1)


def check_history(path, probes):
    if not os.path.isfile(path):
        fail("missing " + path)
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f if l.strip()]
    if len(lines) < 3:
        fail(f"{path}: expected a header and at least 2 rows, got {len(lines)} lines")
    header = lines[0].split(",")
    for col in ["time", "step", "kinetic_energy", "internal_energy", "total_energy", "mass"] + probes:
        if col not in header:
            fail(f"{path}: no column '{col}' (columns: {', '.join(header)})")
    for i, line in enumerate(lines[1:], start=2):
        cells = line.split(",")
        if len(cells) != len(header):
            fail(f"{path}:{i}: {len(cells)} values for {len(header)} columns")
        for name, cell in zip(header, cells):
            v = float(cell)
            # penetration_time is "nan" before the main stage fires the penetrator (docs/deck.md).
            if not math.isfinite(v) and not (name == "penetration_time" and cell == "nan"):
                fail(f"{path}:{i}: column '{name}' is {cell}")
    print(f"history.csv: {len(lines) - 1} rows, {len(header)} columns, all finite")


def check_names(h5, f):
    """Every body and material index in a particle file has its name in the file's attributes."""
    for index, attr in (("body", "body_names"), ("material", "material_names")):
        if index not in f:
            continue
        if attr not in f.attrs:
            fail(f"{h5} has '{index}' indices but no '{attr}' attribute")
        names = json.loads(f.attrs[attr])
        values = f[index][()]
        if len(values) and (values.min() < 0 or values.max() >= len(names)):
            fail(f"{h5}: '{index}' indices {values.min()}..{values.max()} outside the {len(names)} {attr}")


def check_xdmf(out, end_time):
    import h5py

    path = os.path.join(out, "particles.xdmf")
    if not os.path.isfile(path):
        fail("missing " + path)
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        fail(f"{path} is not valid XML: {e}")
    items = [d for d in root.iter("DataItem") if d.get("Format") == "HDF"]
    if not items:
        fail(f"{path} references no HDF5 data")
    files = {}
    for d in items:
        ref = (d.text or "").strip()
        if ":" not in ref:
            fail(f"{path}: malformed HDF reference '{ref}'")
        fname, dset = ref.split(":", 1)
        h5 = os.path.join(out, fname)
        if not os.path.isfile(h5):
            fail(f"{path} references {fname}, which does not exist")
        if h5 not in files:
            try:
                files[h5] = h5py.File(h5, "r")
            except OSError as e:
                fail(f"cannot open {h5}: {e}")
        f = files[h5]
        if dset not in f:
            fail(f"{fname} has no dataset {dset} (referenced by particles.xdmf)")
        dims = tuple(int(x) for x in d.get("Dimensions", "").split())
        if dims and tuple(f[dset].shape) != dims:
            fail(f"{fname}:{dset} has shape {f[dset].shape}, particles.xdmf says {dims}")
    times = []
    for h5 in sorted(files):
        times.append(float(files[h5]["time"][()]))
    if times != sorted(times):
        fail(f"output times are not increasing: {times}")
    if not math.isclose(times[-1], end_time, rel_tol=1e-9):
        fail(f"last output at t = {times[-1]}, summary says end time {end_time}")
    for h5, f in files.items():
        check_names(h5, f)
        f.close()
    print(f"particles.xdmf: {len(files)} outputs, {len(items)} datasets, all present")


def run_ballista(args, command):
    """Runs `ballista COMMAND deck -o out -q [--set ...]` into a fresh folder and returns its
    summary.json, failing unless the run completed and wrote resolved.yaml."""
    if os.path.exists(args.out):
        shutil.rmtree(args.out)
    cmd = [args.ballista, command, args.deck, "-o", args.out, "-q"]
    for s in args.set or []:
        cmd += ["--set", s]
    print("running: " + " ".join(cmd), flush=True)
    p = subprocess.run(cmd, capture_output=True, text=True)
    sys.stdout.write(p.stdout)
    sys.stderr.write(p.stderr)
    if p.returncode != 0:
        fail(f"ballista {command} exited with status {p.returncode}")
    summary_path = os.path.join(args.out, "summary.json")
    if not os.path.isfile(summary_path):
        fail("missing " + summary_path)
    with open(summary_path) as f:
        summary = json.load(f)
    if summary.get("status") != "completed":
        fail(f"summary status is {summary.get('status')!r}: {summary.get('error', '')}")
    if not os.path.isfile(os.path.join(args.out, "resolved.yaml")):
        fail("missing resolved.yaml")
    if command == "run":
        check_units(summary)
    return summary


def numeric_paths(value, path=""):
    """Paths of every number in a summary, arrays' elements as `key[]` (as "units" names them)."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield from numeric_paths(v, f"{path}.{k}" if path else k)
    elif isinstance(value, list):
        for v in value:
            yield from numeric_paths(v, path + "[]")
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        yield path


def check_units(summary):
    """Every number of summary.json has its SI unit in summary["units"] (io/summary_units.cpp)."""
    units = summary.get("units")
    if not isinstance(units, dict):
        fail("summary.json has no units object")
    missing = sorted({p for p in numeric_paths({k: v for k, v in summary.items() if k != "units"})
                      if p not in units})
    if missing:
        fail(f"summary.json numbers without a unit in 'units': {missing[:12]}")
    print(f"summary.json: {len(units)} numbers, each with its unit")


def run_mode(args):
    summary = run_ballista(args, "run")
    probes = summary.get("probes", {})
    wanted = list(dict.fromkeys(list(probes) + (args.probe or [])))
    for name in wanted:
        v = probes.get(name)
        if v is None or not isinstance(v, (int, float)) or not math.isfinite(v):
            fail(f"probe '{name}' missing or not finite in summary.json: {v!r}")
        print(f"probe {name} = {v:.6g}")
    check_history(os.path.join(args.out, "history.csv"), wanted)
    check_xdmf(args.out, summary["statistics"]["end_time"])
    print("OK")


def drive_mode(args):
    summary = run_ballista(args, "drive")
    path = os.path.join(args.out, "history.csv")
    with open(path) as f:
        lines = [l.rstrip("\n") for l in f if l.strip()]
    if len(lines) < 3:
        fail(f"{path}: expected a header and at least 2 rows, got {len(lines)} lines")
    header = lines[0].split(",")
    wanted = ["step", "t"] + [f"F{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
    wanted += [f"sigma_{c}" for c in ("11", "22", "33", "23", "13", "12")]
    wanted += [f"sigma_bar_{c}" for c in ("11", "22", "33", "23", "13", "12")]
    wanted += ["I1", "sqrt_J2", "pressure"]
    for col in wanted:
        if col not in header:
            fail(f"{path}: no column '{col}' (columns: {', '.join(header)})")
    times = []
    for i, line in enumerate(lines[1:], start=2):
        cells = line.split(",")
        if len(cells) != len(header):
            fail(f"{path}:{i}: {len(cells)} values for {len(header)} columns")
        for name, cell in zip(header, cells):
            if not math.isfinite(float(cell)):
                fail(f"{path}:{i}: column '{name}' is {cell}")
        times.append(float(cells[header.index("t")]))
    if any(b <= a for a, b in zip(times, times[1:])):
        fail(f"{path}: times are not strictly increasing")
    if len(lines) - 1 != summary["statistics"]["records"]:
        fail(f"{path}: {len(lines) - 1} rows, summary.json says {summary['statistics']['records']} records")
    print(f"history.csv: {len(lines) - 1} rows, {len(header)} columns, all finite; "
          f"{summary['statistics']['steps']} steps")
    print("OK")


def typo_mode(args):
    os.makedirs(args.out, exist_ok=True)
    with open(args.deck) as f:
        lines = f.readlines()
    pat = re.compile(r"^(\s*)" + re.escape(args.key) + r":")
    line_no = col = None
    for i, line in enumerate(lines):
        m = pat.match(line)
        if m:
            lines[i] = line.replace(args.key + ":", args.typo + ":", 1)
            line_no, col = i + 1, len(m.group(1)) + 1
            break
    if line_no is None:
        fail(f"{args.deck} has no line starting with '{args.key}:'")
    deck = os.path.join(args.out, "typo_deck.yaml")
    with open(deck, "w") as f:
        f.writelines(lines)
    results = os.path.join(args.out, "results")
    if os.path.exists(results):
        shutil.rmtree(results)
    cmd = [args.ballista, "run", deck, "-o", results, "-q"]
    print("running: " + " ".join(cmd), flush=True)
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(f"exit status {p.returncode}; stderr: {p.stderr.strip()}")
    if p.returncode == 0:
        fail("ballista accepted a deck with an unknown key")
    # make test-sanitize: a UBSan abort also exits non-zero (ASan reports go to files there).
    if "runtime error:" in p.stderr:
        fail("UndefinedBehaviorSanitizer report in the failing run")
    where = f"{deck}:{line_no}:{col}:"
    for needle in [where, f"'{args.typo}'", f"did you mean '{args.key}'"]:
        if needle not in p.stderr:
            fail(f"stderr does not contain {needle!r}")
    if os.path.exists(results):
        fail("a results folder was created for an invalid deck")
    print("OK")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="mode", required=True)
    r = sub.add_parser("run")
    d = sub.add_parser("drive")
    t = sub.add_parser("typo")
    for p in (r, d, t):
        p.add_argument("--ballista", required=True)
        p.add_argument("--deck", required=True)
        p.add_argument("--out", required=True)
    r.add_argument("--set", action="append", help="deck override key.path=value (repeatable)")
    r.add_argument("--probe", action="append", help="probe that must be present and finite")
    d.add_argument("--set", action="append", help="deck override key.path=value (repeatable)")
    t.add_argument("--key", required=True, help="key to misspell (its first occurrence)")
    t.add_argument("--typo", required=True, help="the misspelling")
    args = ap.parse_args()
    {"run": run_mode, "drive": drive_mode, "typo": typo_mode}[args.mode](args)


if __name__ == "__main__":
    main()
