"""What the thesis-scale study scripts share: run a deck into a folder once (a folder that already
holds a summary.json is a finished run and is not run again), read its summary, and the command
line every such script takes (--ballista, --out, --table-only)."""
import argparse
import json
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))


def run_once(ballista, deck, folder, sets):
    """`ballista run DECK -o FOLDER` with the --set arguments `sets`, unless FOLDER is finished."""
    if os.path.exists(os.path.join(folder, "summary.json")):
        return
    cmd = [ballista, "run", deck, "-o", folder, "-q", "--no-plots"] + list(sets)
    print(" ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def summary(folder):
    """The run's summary.json, or None if it has not run."""
    path = os.path.join(folder, "summary.json")
    return json.load(open(path)) if os.path.exists(path) else None


def final_depth(folder):
    """The penetrator's final depth [m], or None if the run has not run."""
    s = summary(folder)
    return None if s is None else s["penetration"]["final_depth"]


def study_arguments(doc, out):
    """The parser every study script starts from; `doc` is its module docstring."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--ballista", default="build/ballista")
    ap.add_argument("--out", default=out)
    ap.add_argument("--table-only", action="store_true", help="run nothing; print the table of what has run")
    return ap
