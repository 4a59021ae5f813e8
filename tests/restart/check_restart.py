#!/usr/bin/env python3
"""Checkpoint/restart check (issue 16, docs/restart.md): a run restarted from a checkpoint must
reproduce the uninterrupted run bitwise: history.csv and every other CSV byte for byte, every
dataset of every particle file, the XDMF index, and summary.json apart from wall-clock entries.

  check_restart.py BALLISTA DECK WORKDIR --mode copy|kill [--set k=v ...] [--restart-threads N]

copy: the reference run writes checkpoints; a copy of its folder is restarted from its newest
      checkpoint (the rows and particle files written after it are cut back and rewritten).
kill: a second run is killed with SIGKILL as soon as it has written a checkpoint after the first
      step, then restarted (on --restart-threads threads) and compared with the reference.
term: the same with SIGTERM, which the run answers by checkpointing its current step and exiting
      with status 4 ("interrupted" in summary.json).
"""
import argparse, glob, json, os, shutil, signal, subprocess, sys, time

import h5py
import numpy as np

WALL_KEYS = {"wall_time", "particle_steps_per_second", "deck", "restarted_from", "timing", "threads"}


def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.exit(f"FAILED ({r.returncode}): {' '.join(cmd)}\n{r.stdout[-3000:]}")
    return r.stdout


def strip(obj):
    if isinstance(obj, dict):
        return {k: strip(v) for k, v in obj.items() if k not in WALL_KEYS}
    if isinstance(obj, list):
        return [strip(v) for v in obj]
    return obj


def compare(ref, other):
    bad = []
    for f in sorted(glob.glob(os.path.join(ref, "*.csv"))):
        g = os.path.join(other, os.path.basename(f))
        if not os.path.exists(g) or open(f, "rb").read() != open(g, "rb").read():
            bad.append(os.path.basename(f))
    for name in ("particles.xdmf",):
        f, g = os.path.join(ref, name), os.path.join(other, name)
        if open(f, "rb").read() != open(g, "rb").read():
            bad.append(name)
    ref_h5 = sorted(glob.glob(os.path.join(ref, "particles_*.h5")))
    other_h5 = sorted(glob.glob(os.path.join(other, "particles_*.h5")))
    if [os.path.basename(f) for f in ref_h5] != [os.path.basename(f) for f in other_h5]:
        bad.append(f"particle files {len(ref_h5)} vs {len(other_h5)}")
    for f in ref_h5:
        g = os.path.join(other, os.path.basename(f))
        if not os.path.exists(g):
            continue
        with h5py.File(f, "r") as a, h5py.File(g, "r") as b:
            if set(a.keys()) != set(b.keys()):
                bad.append(os.path.basename(f) + " datasets")
                continue
            for k in a.keys():
                if np.asarray(a[k][()]).tobytes() != np.asarray(b[k][()]).tobytes():
                    bad.append(f"{os.path.basename(f)}:{k}")
    sa = strip(json.load(open(os.path.join(ref, "summary.json"))))
    sb = strip(json.load(open(os.path.join(other, "summary.json"))))
    if sa != sb:
        bad.append("summary.json")
    return bad, len(ref_h5)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("ballista")
    ap.add_argument("deck")
    ap.add_argument("workdir")
    ap.add_argument("--mode", choices=["copy", "kill", "term"], required=True)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--restart-threads", type=int, default=0)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--keep-only", type=int, default=-1,
                    help="copy mode: restart from the reference's checkpoint of this index (0 = oldest kept) "
                         "after removing the newer ones (default: the newest)")
    a = ap.parse_args()
    shutil.rmtree(a.workdir, ignore_errors=True)
    os.makedirs(a.workdir)
    ref, other = os.path.join(a.workdir, "reference"), os.path.join(a.workdir, "restarted")
    sets = sum([["--set", s] for s in a.set], [])
    base = [a.ballista, "run", a.deck, "-q", "--no-plots", "--threads", str(a.threads)] + sets
    run(base + ["-o", ref])
    cks = sorted(glob.glob(os.path.join(ref, "checkpoints", "checkpoint_*.h5")))
    if len(cks) < 2:
        sys.exit(f"the reference run wrote {len(cks)} checkpoints; the check needs a mid-run one")
    restart_threads = ["--threads", str(a.restart_threads or a.threads)]
    if a.mode == "copy":
        shutil.copytree(ref, other)
        pick = cks[a.keep_only] if a.keep_only >= 0 else cks[-1]
        for c in cks:
            if c > pick:
                os.remove(os.path.join(other, "checkpoints", os.path.basename(c)))
        resumed_at = os.path.basename(pick)
    else:
        p = subprocess.Popen(base + ["-o", other], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.time() + 600
        while time.time() < deadline and p.poll() is None:
            found = [c for c in glob.glob(os.path.join(other, "checkpoints", "checkpoint_*.h5"))
                     if not c.endswith("checkpoint_000000000000.h5")]
            if found:
                break
            time.sleep(0.01)
        if p.poll() is not None:
            sys.exit("the run ended before it could be killed; lengthen it")
        p.send_signal(signal.SIGKILL if a.mode == "kill" else signal.SIGTERM)
        rc = p.wait()
        if a.mode == "term":
            # SIGTERM: the run checkpoints the step it is in and exits with status 4, "interrupted".
            if rc != 4:
                sys.exit(f"SIGTERM: exit status {rc}, expected 4 (interrupted)")
            status = json.load(open(os.path.join(other, "summary.json")))["status"]
            if status != "interrupted":
                sys.exit(f"SIGTERM: summary status '{status}', expected 'interrupted'")
        left = sorted(glob.glob(os.path.join(other, "checkpoints", "checkpoint_*.h5")))
        resumed_at = os.path.basename(left[-1])
    out = run([a.ballista, "run", "--restart", other, "-q", "--no-plots"] + restart_threads + sets)
    bad, nfiles = compare(ref, other)
    print(f"{a.mode}: restarted from {resumed_at}; compared history.csv, {nfiles} particle files, "
          f"particles.xdmf, summary.json: {'all identical' if not bad else 'DIFFERENT: ' + ', '.join(bad)}")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
