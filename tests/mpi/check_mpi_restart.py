#!/usr/bin/env python3
"""Checkpoint and restart on several MPI ranks (issue 16 item 3, docs/restart.md, docs/parallel.md).

  check_mpi_restart.py BALLISTA DECK WORKDIR [--pairs 2:2,2:1,1:2,2:4] [--kill 2] [--term 2]
                       [--set k=v ...] [--tol 1e-11] [--fields-bitwise]

For each pair W:R: the deck runs uninterrupted on W ranks with checkpoints; a copy of its results
folder keeps only a checkpoint from the middle of the run and is restarted from it on R ranks
(R = 1: the plain serial program). With W = R the restarted run must be bitwise the uninterrupted
one (history.csv and the XDMF byte for byte, every particle dataset, the summary apart from wall
clock), because each rank gets its own particles back in their order and the decomposition's cuts.
With W != R the particles are cut anew, so it must agree within --tol (check_mpi.compare); with
--fields-bitwise every particle field must be bitwise and only the sums over ranks within --tol.
--kill W: a run on W ranks is killed with SIGKILL (its whole process group: mpirun and the ranks)
once it has written a checkpoint after the start, restarted on W ranks, and must end bitwise equal
to the uninterrupted run.
--term W: the same with SIGTERM sent to every rank (a batch system's notice): the ranks agree to
stop, checkpoint the step they are in, exit with status 4 ("interrupted"; mpirun returns non-zero),
and the restart must again end bitwise equal to the uninterrupted run.
"""
import argparse, glob, json, os, shutil, signal, subprocess, sys, time

import h5py
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(here, "..", "restart")]
import check_mpi  # noqa: E402
from check_mpi import compare  # noqa: E402
from check_restart import strip  # noqa: E402  (summary.json without its wall-clock entries)
ENV = dict(os.environ, OMP_WAIT_POLICY="passive")


def launcher(n, ballista):
    if n == 1:
        return [ballista]
    return ["mpirun", "--oversubscribe", "--allow-run-as-root", "-np", str(n), ballista]


def run(cmd):
    check_mpi.run(cmd, ENV)


def bitwise(ref, other):
    bad = []
    csvs = [os.path.relpath(f, ref) for f in glob.glob(os.path.join(ref, "*.csv")) + glob.glob(os.path.join(ref, "tracks", "*.csv"))]
    for name in sorted(csvs) + ["particles.xdmf"]:
        if not os.path.exists(os.path.join(other, name)):
            bad.append(name + " missing")
            continue
        if open(os.path.join(ref, name), "rb").read() != open(os.path.join(other, name), "rb").read():
            bad.append(name)
    fa = sorted(glob.glob(os.path.join(ref, "particles_*.h5")))
    fb = sorted(glob.glob(os.path.join(other, "particles_*.h5")))
    if [os.path.basename(f) for f in fa] != [os.path.basename(f) for f in fb]:
        return bad + [f"particle files {len(fa)} vs {len(fb)}"]
    for f, g in zip(fa, fb):
        with h5py.File(f, "r") as A, h5py.File(g, "r") as B:
            for k in A.keys():
                if k not in B or not np.array_equal(np.asarray(A[k]), np.asarray(B[k])):
                    bad.append(f"{os.path.basename(f)}:{k}")
    sa, sb = (strip(json.load(open(os.path.join(d, "summary.json")))) for d in (ref, other))
    if sa != sb:
        bad.append("summary.json")
    return bad



def session_members(sid):
    """Pids of the live processes in session sid. Open MPI's mpirun puts each rank in a process
    group of its own, so killing mpirun's group leaves the ranks running; the session (started by
    Popen's start_new_session) holds them all."""
    pids = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            stat = open(f"/proc/{d}/stat").read()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2:].split()
        # fields[0] is the state (field 3 of proc(5)), fields[3] the session id (field 6).
        if fields[0] != "Z" and int(fields[3]) == sid:
            pids.append(int(d))
    return pids


def kill_session(sid):
    """SIGKILL to mpirun and every rank at once, as a crash of the whole job would."""
    for pid in session_members(sid):
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


def rank_pids(sid, name):
    """The ranks of the job in session sid: its processes running the program called name."""
    def comm(pid):
        try:
            return open(f"/proc/{pid}/comm").read().strip()
        except OSError:
            return ""
    return [pid for pid in session_members(sid) if pid != sid and comm(pid) == name[:15]]


def term_ranks(p, name):
    """SIGTERM to every rank, as a batch system does at a time limit or on scancel (Slurm signals
    each task of the job). Not through mpirun: Open MPI 4.1's mpirun passes a SIGTERM on only
    odls_base_sigkill_timeout seconds later and SIGKILLs the ranks as long again after that, so a
    test through it measures whether this machine wrote the checkpoint within that grace (on a
    loaded machine it did not always), not what the program does (docs/restart.md)."""
    for pid in rank_pids(p.pid, name):
        try:
            os.kill(pid, signal.SIGTERM)
        except ProcessLookupError:
            pass


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("ballista")
    ap.add_argument("deck")
    ap.add_argument("workdir")
    ap.add_argument("--pairs", default="2:2,2:1,1:2,2:4")
    ap.add_argument("--kill", type=int, default=0)
    ap.add_argument("--term", type=int, default=0)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--tol", type=float, default=1e-11)
    ap.add_argument("--fields-bitwise", action="store_true",
                    help="restarts onto another rank count: every particle field bitwise too (only the sums over "
                         "ranks within --tol)")
    ap.add_argument("--checkpoint", type=int, default=-1,
                    help="restart from this checkpoint (index into the sorted list; default: the middle one)")
    a = ap.parse_args()
    shutil.rmtree(a.workdir, ignore_errors=True)
    os.makedirs(a.workdir)
    sets = sum((["--set", s] for s in a.set + ["output.checkpoint_keep=100"]), [])
    common = ["-q", "--no-plots", "--threads", "1"]
    refs = {}

    def reference(w):
        if w not in refs:
            refs[w] = os.path.join(a.workdir, f"uninterrupted_{w}")
            run(launcher(w, a.ballista) + ["run", a.deck, "-o", refs[w]] + common + sets)
        return refs[w]

    failures = []
    for pair in [p for p in a.pairs.split(",") if p]:
        w, r = (int(x) for x in pair.split(":"))
        ref = reference(w)
        cks = sorted(glob.glob(os.path.join(ref, "checkpoints", "checkpoint_*.h5")))
        if len(cks) < 3:
            sys.exit(f"{ref}: only {len(cks)} checkpoints; shorten output.checkpoint_interval")
        keep = cks[len(cks) // 2 if a.checkpoint < 0 else min(a.checkpoint, len(cks) - 1)]
        out = os.path.join(a.workdir, f"restart_{w}_on_{r}")
        shutil.copytree(ref, out)
        for f in glob.glob(os.path.join(out, "checkpoints", "checkpoint_*.h5")):
            if os.path.basename(f) != os.path.basename(keep):
                os.remove(f)
        run(launcher(r, a.ballista) + ["run", "--restart", out] + common)
        if w == r:
            bad = bitwise(ref, out)
            print(f"written on {w}, restarted on {r} from {os.path.basename(keep)}: "
                  + ("bitwise identical" if not bad else "DIFFERS: " + ", ".join(bad[:8])))
        else:
            worst, bad = compare(ref, out, a.tol, 0.0 if a.fields_bitwise else None)
            print(f"written on {w}, restarted on {r} from {os.path.basename(keep)}: largest relative difference "
                  f"{worst:.3g}" + ("" if not bad else " -- FAILED"))
        failures += [f"{w}:{r}: {b}" for b in bad]
    for sig, w in ((signal.SIGKILL, a.kill), (signal.SIGTERM, a.term)):
        if not w:
            continue
        ref = reference(w)
        out = os.path.join(a.workdir, f"{sig.name}_{w}")
        log_path = os.path.join(a.workdir, f"{sig.name}_{w}.log")
        log = open(log_path, "w")
        p = subprocess.Popen(launcher(w, a.ballista) + ["run", a.deck, "-o", out] + common + sets,
                             stdout=log, stderr=subprocess.STDOUT, env=ENV, start_new_session=True)
        deadline = time.time() + 120
        while time.time() < deadline and p.poll() is None:
            if len(glob.glob(os.path.join(out, "checkpoints", "checkpoint_*.h5"))) >= 2:
                break
            time.sleep(0.01)
        stopped = p.poll() is None
        if stopped:
            # SIGKILL: mpirun and every rank at once (nothing can be written). SIGTERM: to every
            # rank; they agree, checkpoint the step they are in and exit 4.
            if sig == signal.SIGKILL:
                kill_session(p.pid)
            else:
                term_ranks(p, os.path.basename(a.ballista))
        code = p.wait()
        log.close()
        if sig == signal.SIGKILL:
            # A rank still alive holds the results folder (io/run_folder.hpp): the restart waits
            # until every process of the job's session is gone.
            for _ in range(1000):
                if not session_members(p.pid):
                    break
                kill_session(p.pid)
                time.sleep(0.01)
        if not stopped:
            failures.append(f"{sig.name}: the run ended before the signal; lengthen the deck")
            continue
        if sig == signal.SIGTERM:
            if not os.path.exists(os.path.join(out, "summary.json")):
                failures.append(f"SIGTERM: exit {code} and no summary.json; what the run printed:\n"
                                + open(log_path).read()[-4000:])
                continue
            status = json.load(open(os.path.join(out, "summary.json")))["status"]
            # Each rank exits 4, and mpirun returns non-zero when a rank did (Open MPI 4.1: 4).
            if code == 0 or status != "interrupted":
                failures.append(f"SIGTERM: exit {code}, status {status} (expected non-zero, interrupted)")
        run(launcher(w, a.ballista) + ["run", "--restart", out] + common)
        bad = bitwise(ref, out)
        print(f"{sig.name} on {w} ranks, restarted on {w}: "
              + ("bitwise identical" if not bad else "DIFFERS: " + ", ".join(bad[:8])))
        failures += [f"{sig.name}: {b}" for b in bad]
    if failures:
        print("\n".join(failures[:40]))
        sys.exit(1)
    print("OK")


if __name__ == "__main__":
    main()
