#!/usr/bin/python3
"""Inspect Ballista particle output (particles_NNNNNN.h5 + particles.xdmf).

Usage:
  read_output.py DIR                      list outputs: index, time, step, points, fields
  read_output.py DIR --field NAME [-i K]  print field NAME of output K (default: last)
  read_output.py DIR --check              check particles.xdmf: XML parses, every referenced
                                          dataset exists with the declared shape

As a module: load(dir, index=-1) -> dict of numpy arrays (plus 'time' and 'step').
Needs h5py and numpy (Debian: python3-h5py python3-numpy).
"""
import argparse
import glob
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def output_files(directory):
    """Sorted list of particles_NNNNNN.h5 files in directory."""
    return sorted(glob.glob(os.path.join(directory, "particles_[0-9]*.h5")))


def load(directory, index=-1):
    """All datasets of one output as numpy arrays; index counts outputs (negative from the end)."""
    files = output_files(directory)
    if not files:
        raise FileNotFoundError(f"no particles_*.h5 in {directory}")
    with h5py.File(files[index], "r") as h:
        data = {name: h[name][()] for name in h.keys()}
    data["time"] = float(data["time"])
    data["step"] = int(data["step"])
    return data


def list_outputs(directory):
    for k, path in enumerate(output_files(directory)):
        with h5py.File(path, "r") as h:
            n = h["x"].shape[0]
            fields = [f"{name}{list(h[name].shape[1:]) or ''}" for name in h.keys()
                      if name not in ("time", "step", "vertex_cells", "domain_points", "domain_cells")]
            domains = "domains" if "domain_cells" in h else ""
            print(f"{k:6d}  t={float(h['time'][()]):.9g}  step={int(h['step'][()])}  "
                  f"points={n}  {' '.join(fields)} {domains}".rstrip())


def check_xdmf(directory):
    """Returns a list of problems found in particles.xdmf (empty if none)."""
    path = os.path.join(directory, "particles.xdmf")
    problems = []
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        return [f"{path}: {e}"]
    for item in root.iter("DataItem"):
        ref = (item.text or "").strip()
        if ":" not in ref:
            problems.append(f"DataItem without file:dataset reference: {ref!r}")
            continue
        fname, dset = ref.split(":", 1)
        dims = tuple(int(d) for d in item.get("Dimensions", "").split())
        try:
            with h5py.File(os.path.join(directory, fname), "r") as h:
                if dset not in h:
                    problems.append(f"{ref}: dataset missing")
                elif h[dset].shape != dims:
                    problems.append(f"{ref}: shape {h[dset].shape}, XDMF says {dims}")
        except OSError as e:
            problems.append(f"{ref}: {e}")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", help="output directory")
    ap.add_argument("--field", help="print this field")
    ap.add_argument("-i", "--index", type=int, default=-1, help="output index (default: last)")
    ap.add_argument("--check", action="store_true", help="validate particles.xdmf")
    args = ap.parse_args()
    if args.check:
        problems = check_xdmf(args.dir)
        for p in problems:
            print(p)
        return 1 if problems else 0
    if args.field:
        data = load(args.dir, args.index)
        if args.field not in data:
            print(f"no field {args.field!r}; have {sorted(data)}", file=sys.stderr)
            return 1
        np.set_printoptions(precision=17, threshold=sys.maxsize, linewidth=200)
        print(f"# t={data['time']:.17g} step={data['step']} {args.field}")
        print(data[args.field])
        return 0
    list_outputs(args.dir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
