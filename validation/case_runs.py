"""What the thesis-scale study scripts share: run a deck into a folder once (a folder that already
holds a summary.json is a finished run and is not run again, unless it was interrupted: then it
continues from its last checkpoint; a run that stops with an error is reported and the study goes
on), read its summary and its history after the shot, and the command line every such script
takes (--ballista, --out, --table-only)."""
import argparse
import csv
import json
import math
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))


def run_once(ballista, deck, folder, sets):
    """`ballista run DECK -o FOLDER` with the --set arguments `sets`, unless FOLDER is finished; an
    interrupted run (SIGTERM, a batch system's notice) continues from its last checkpoint, with the
    deck it was started with and the thread count of `sets`."""
    s = summary(folder)
    if s is not None and s.get("status") != "interrupted":
        return
    if s is None:
        cmd = [ballista, "run", deck, "-o", folder, "-q", "--no-plots"] + list(sets)
    else:
        threads = [a for i, a in enumerate(sets) if a == "--threads" or (i > 0 and sets[i - 1] == "--threads")]
        cmd = [ballista, "run", "--restart", folder, "-q", "--no-plots"] + threads
    print(" ".join(cmd), flush=True)
    if subprocess.run(cmd).returncode != 0:
        print(f"the run in {folder} stopped with an error (its summary.json says why)", flush=True)


def summary(folder):
    """The run's summary.json, or None if it has not run."""
    path = os.path.join(folder, "summary.json")
    return json.load(open(path)) if os.path.exists(path) else None


def after_firing(folder, column, times):
    """history.csv's `column` at each time [s] after the main stage began, None past the run's end:
    the first row at or after it. (perforation_convergence.depth_at_times takes the nearest row
    within 0.2 us, for the jet's dense rows; the thesis-scale runs' rows are up to ~1 us apart, and
    this reads a run still going, from its penetration_time column.)"""
    path = os.path.join(folder, "history.csv")
    if not os.path.exists(path):
        return [None] * len(times)
    rows = [(float(r["penetration_time"]), float(r[column])) for r in csv.DictReader(open(path))
            if not math.isnan(float(r["penetration_time"]))]
    found = []
    for t in times:
        past = [v for (tp, v) in rows if tp >= t]
        found.append(past[0] if past else None)
    return found


def final_depth(folder):
    """The penetrator's final depth [m]; None if the run has not run or stopped with an error."""
    s = summary(folder)
    return None if s is None or s["status"] != "completed" else s["penetration"]["final_depth"]


def state(folder):
    """'not run', 'failed at t = ... us' or 'completed'."""
    s = summary(folder)
    if s is None:
        return "not run"
    if s["status"] != "completed":
        return f"failed at t = {1e6 * s['statistics']['end_time']:.0f} us"
    return "completed"


def study_arguments(doc, out):
    """The parser every study script starts from; `doc` is its module docstring."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--ballista", default="build/ballista")
    ap.add_argument("--out", default=out)
    ap.add_argument("--table-only", action="store_true", help="run nothing; print the table of what has run")
    return ap


def add_deck_changes(ap):
    """The options of a study of a confined target: a hole in the struck face's load, and deck
    changes for every run, whose folders a tag names apart."""
    ap.add_argument("--hole-radius", type=float, default=0.0,
                    help="m; no overburden on the top face within this radius (thesis §6.2, Fig. 6.14)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a deck change for every run of the study (repeatable)")
    ap.add_argument("--tag", default="", help="appended to the run folders' names")


def parse_study(ap):
    """The parsed options of a parser given add_deck_changes; a deck change without a tag is refused."""
    a = ap.parse_args()
    if a.set and not a.tag:
        ap.error("--set needs --tag, so that its runs do not mix with the deck's own")
    return a
