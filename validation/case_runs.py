"""What the thesis-scale study scripts share: run a deck into a folder once (a folder that already
holds a summary.json is a finished run and is not run again, unless it was interrupted: then it
continues from its last checkpoint; a run that stops with an error is reported and the study goes
on), read its summary, and the command line every such script takes (--ballista, --out,
--table-only)."""
import argparse
import json
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
