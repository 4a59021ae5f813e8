"""Results-folder cases of the fuzz harness (tools/fuzz_decks.py; issue 35).

  concurrent:<stem>  two `ballista run DECK -o SAME` at once. The second starts only when the first
                     has certainly begun its steps (its first particle file exists) and is certainly
                     still running: either the first is held (SIGSTOP to its process group) until the
                     second has ended, then continued ("paused"), or the first runs a deck of a few
                     seconds and the second starts 0.1-1 s later ("overlapping"). The second is the
                     same command, the same deck with another output interval, another deck, or
                     `run --restart SAME` (the first writes checkpoints). Expected: the second is
                     refused (non-zero exit, a message: the folder is in use; the first certainly
                     holds the folder, it has written results) and the first completes with a
                     consistent folder: summary.json "completed", particles.xdmf well-formed XML,
                     every particles_*.h5 it references present and every one present referenced,
                     history.csv with one header and non-decreasing time. Class
                     concurrent_runs_mixed: both exit 0, the first fails (the second disturbed it),
                     or the folder is inconsistent. The classification does not depend on timing: were the
                     first run over before the second started (a machine many times faster), the
                     case is a rerun into a finished folder and is classified as such (noted).
  userfile:<stem>    a folder holding user files (notes.tmp, mydata.csv, sub/keep.dat, ...) and no
                     Ballista run; a run into it (`-o F`, `-o .` from inside it, with --overwrite,
                     `-o F/mydata.csv`), or into a folder holding an earlier run and user files
                     added since (a new run, or `--restart F`). Every user file must still exist
                     byte-identical afterwards, whether the run was refused or not; class
                     user_file_deleted otherwise. (Intended: a non-empty folder without a Ballista
                     run is refused unless --overwrite is given; a run deletes only its own files.)
The unmutated cases (--baseline) run the deck into the folder twice, one after the other (a rerun
into a Ballista folder must be accepted; the folder must be consistent), and once into a new folder.
"""
import hashlib
import json
import os
import re
import shlex
import signal
import sys
import time
import xml.etree.ElementTree as ET

COMMON = ["--no-plots", "-q", "--threads", "1"]
# deck -> reduction (--set); runs of ~0.4-0.9 s with 10-17 particle files
CONCURRENT_DECKS = {
    "taylor_bar_mpm": {"grid.cell_size": "0.8e-3", "output.interval": "5.0e-6"},
    "pd_kalthoff_winkler": {"grid.cell_size": "2.0e-3", "output.interval": "5.0e-6"},
}
# the overlapping variant's first run: 2-2.5 s at one thread on the idle 2-core machine (the second
# starts <= 1 s after the first's first particle file, so the first is still running)
LONG_DECKS = {
    "taylor_bar_mpm": {"grid.cell_size": "0.5e-3", "output.interval": "5.0e-6"},
    "pd_kalthoff_winkler": {"grid.cell_size": "1.2e-3", "output.interval": "5.0e-6"},
}
USERFILE_DECKS = {
    "taylor_bar_mpm": {"grid.cell_size": "0.8e-3", "simulation.end_time": "5.0e-6"},
    "pd_kalthoff_winkler": {"grid.cell_size": "2.0e-3", "simulation.end_time": "4.0e-6"},
}
USER_FILES = {
    "notes.tmp": b"my notes: do not delete\n",
    "mydata.csv": b"time,value\n0,1\n1,2\n",
    "README.txt": b"measurements of 2026-11-20\n",
    ".hidden": b"x\n",
    "sub/keep.dat": bytes(range(256)),
    "draft.yaml.tmp": b"simulation: {end_time: 1}\n",
    "experiment.h5": b"\x89HDF\r\n\x1a\n" + bytes(64),
    "run.log": b"my own log\n",
}

def _sets(d):
    out = []
    for k, v in d.items():
        out += ["--set", f"{k}={v}"]
    return out


def _write_deck(path, case_dir, name="deck.yaml"):
    with open(path, "rb") as f:
        data = f.read()
    with open(os.path.join(case_dir, name), "wb") as f:
        f.write(data)


# ---------------------------------------------------------------------------------------------
# folder consistency
# ---------------------------------------------------------------------------------------------
def folder_problems(folder):
    """What makes a results folder inconsistent ([] when it is a finished run's folder)."""
    probs = []
    try:
        with open(os.path.join(folder, "summary.json")) as f:
            st = json.load(f).get("status")
        if st != "completed":
            probs.append(f"summary.json status {st!r}")
    except (OSError, ValueError, AttributeError) as e:
        probs.append(f"summary.json unreadable ({type(e).__name__})")
    present = {n for n in os.listdir(folder) if re.fullmatch(r"particles_\d+\.h5", n)} if os.path.isdir(folder) \
        else set()
    try:
        root = ET.parse(os.path.join(folder, "particles.xdmf")).getroot()
        refs = {(d.text or "").strip().split(":")[0] for d in root.iter("DataItem") if d.get("Format") == "HDF"}
        missing = sorted(refs - present)
        extra = sorted(present - refs)
        if missing:
            probs.append(f"particles.xdmf references missing {', '.join(missing[:3])}"
                         f"{' ...' if len(missing) > 3 else ''} ({len(missing)})")
        if extra:
            probs.append(f"{len(extra)} particle file(s) not in particles.xdmf ({', '.join(extra[:3])})")
    except (OSError, ET.ParseError) as e:
        probs.append(f"particles.xdmf not well-formed ({str(e)[:100]})")
    try:
        with open(os.path.join(folder, "history.csv")) as f:
            rows = f.read().splitlines()
        head = rows[0] if rows else ""
        if sum(1 for r in rows if r == head) != 1:
            probs.append("history.csv header repeated")
        last = -float("inf")
        for i, r in enumerate(rows[1:]):
            try:
                t = float(r.split(",")[0])
            except ValueError:
                probs.append(f"history.csv row {i + 2} not a number: {r[:60]}")
                break
            if t < last:
                probs.append(f"history.csv time goes back at row {i + 2} ({t:g} after {last:g})")
                break
            last = t
    except OSError:
        probs.append("no history.csv")
    return probs


# ---------------------------------------------------------------------------------------------
# concurrent runs into one folder
# ---------------------------------------------------------------------------------------------
def make_concurrent(rng, stem, path, case_dir, ballista, mut, examples_dir):
    _write_deck(path, case_dir)
    plan = {"folder": "out"}
    if not mut:
        cmd = [ballista, "run", "deck.yaml", "-o", "out"] + COMMON + _sets(CONCURRENT_DECKS[stem])
        plan.update(first=cmd, second=cmd, mode="sequential")
        return plan, ["baseline: the same run twice, one after the other"]
    mode = "paused" if rng.random() < 0.8 else "overlapping"
    red = LONG_DECKS[stem] if mode == "overlapping" else CONCURRENT_DECKS[stem]
    variant = rng.choice(["same", "same", "other_sets", "other_deck", "restart"])
    first_sets = dict(red)
    if variant == "restart":
        first_sets["output.checkpoint_interval"] = "2.0e-6"
    first = [ballista, "run", "deck.yaml", "-o", "out"] + COMMON + _sets(first_sets)
    if variant == "same":
        second = list(first)
    elif variant == "other_sets":
        second = [ballista, "run", "deck.yaml", "-o", "out"] + COMMON + _sets(dict(red, **{
            "output.interval": "1.0e-5"}))
    elif variant == "other_deck":
        other = next(s for s in CONCURRENT_DECKS if s != stem)
        _write_deck(os.path.join(examples_dir, other + ".yaml"), case_dir, "other.yaml")
        second = [ballista, "run", "other.yaml", "-o", "out"] + COMMON + _sets(CONCURRENT_DECKS[other])
    else:
        second = [ballista, "run", "--restart", "out"] + COMMON
    plan.update(first=first, second=second, mode=mode, variant=variant,
                delay=round(rng.uniform(0.1, 1.0), 2) if mode == "overlapping" else 0.0)
    if mode == "paused":
        desc = f"second run ({variant}) while the first is stopped (SIGSTOP) after its first particle file"
    else:
        desc = f"second run ({variant}) {plan['delay']} s after the first's first particle file (first: {red})"
    return plan, [desc]


def _ready(folder, need_checkpoint):
    if not os.path.exists(os.path.join(folder, "particles_000000.h5")):
        return False
    if need_checkpoint:
        d = os.path.join(folder, "checkpoints")
        return os.path.isdir(d) and any(n.endswith(".h5") for n in os.listdir(d))
    return True


FATAL = ("signal", "uncaught", "hang", "out_of_memory", "silent_failure", "error_too_long", "runaway_output")


def execute_concurrent(case, case_dir, a, rn):
    plan = case["plan"]
    folder = os.path.join(case_dir, plan["folder"])
    if plan["mode"] == "sequential":
        r1, _ = rn.run_cmd(plan["first"], case_dir, a, "a.", case_dir, folder)
        if r1["class"] != "ok":
            return dict(r1, detail=f"first run: {r1['detail']} {r1['message']}"[:1000])
        r2, _ = rn.run_cmd(plan["second"], case_dir, a, "b.", case_dir, folder)
        r2["wall"] = round(r1["wall"] + r2["wall"], 3)
        if r2["class"] != "ok":
            return dict(r2, detail=f"a rerun into the finished folder: {r2['detail']} {r2['message']}"[:1000])
        probs = folder_problems(folder)
        if probs:
            return dict(r2, **{"class": "concurrent_runs_mixed", "detail": "after two runs one after the other: "
                               + "; ".join(probs)})
        return r2
    ha = rn.start_cmd(plan["first"], case_dir, a, os.path.join(case_dir, "a.stdout.txt"),
                      os.path.join(case_dir, "a.stderr.txt"))
    t0 = time.monotonic()
    notes = []
    stopped = None
    try:
        while not _ready(folder, plan["variant"] == "restart"):
            if ha["p"].poll() is not None or time.monotonic() - t0 > a.time_limit:
                break
            time.sleep(0.01)
        if plan["mode"] == "paused" and ha["p"].poll() is None:
            os.killpg(ha["p"].pid, signal.SIGSTOP)
            stopped = time.monotonic()
        elif plan["mode"] == "overlapping":
            time.sleep(plan["delay"])
        first_running = ha["p"].poll() is None
        if not first_running:
            notes.append("not concurrent: the first run had ended before the second started")
        hb = rn.start_cmd(plan["second"], case_dir, a, os.path.join(case_dir, "b.stdout.txt"),
                          os.path.join(case_dir, "b.stderr.txt"))
        rawb = rn.finish_cmd(hb, a, case_dir)
    finally:
        if stopped is not None:
            ha["paused"] += time.monotonic() - stopped
            try:
                os.killpg(ha["p"].pid, signal.SIGCONT)
            except ProcessLookupError:
                pass
    rawa = rn.finish_cmd(ha, a, case_dir)
    ra = rn.classify(rawa, a, folder)
    rb = rn.classify(rawb, a, folder)
    wall = round(ra["wall"] + rb["wall"], 3)
    for who, r in (("first run", ra), ("second run", rb)):
        if r["class"] in FATAL:
            return dict(r, wall=wall, detail=f"{who}: {r['detail']} {r['message']}"[:1000])
    ea, eb = ra["exit"] == 0, rb["exit"] == 0
    probs = folder_problems(folder) if (ea or eb) else []
    tail = (" | " + "; ".join(notes)) if notes else ""
    if not first_running:  # a rerun into a finished folder: both must complete
        if ea and eb and not probs:
            return dict(rb, wall=wall, detail=tail[3:])
        if not (ea and eb):
            r = rb if not eb else ra
            return dict(r, wall=wall, detail=f"{r['detail']} {r['message']}{tail}"[:1000])
        return dict(rb, wall=wall, **{"class": "concurrent_runs_mixed", "detail": "; ".join(probs) + tail})
    if ea and eb:
        detail = "both runs exit 0 into one folder" + (": " + "; ".join(probs) if probs else
                                                        " (folder looks consistent)")
        return dict(rb, wall=wall, **{"class": "concurrent_runs_mixed", "detail": detail[:1000]})
    if not ea:
        # the first run was certainly writing its results when the second started: it must complete
        # (it holds the folder); its failure is the second run's interference
        return dict(ra, wall=wall, **{"class": "concurrent_runs_mixed",
                                      "detail": (f"the first run, already writing into the folder when the second "
                                                 f"started, failed (exit {ra['exit']}: {ra['message'][:200]}); the "
                                                 f"second exited {rb['exit']}")[:1000]})
    if probs:
        return dict(rb, wall=wall, **{"class": "concurrent_runs_mixed",
                                      "detail": "the second run was refused but the folder is inconsistent: "
                                                + "; ".join(probs)})
    return dict(rb, wall=wall, detail=f"the second run was refused ({rb['wall']:.2f} s): {rb['message'][:200]}")


def repro_concurrent(case, case_dir, b):
    plan = case["plan"]

    def q(cmd):
        return "\"$B\" " + " ".join(shlex.quote(c) for c in cmd[1:])
    head = (f"#!/bin/sh\n# fuzz case {case['index']} ({case['source']}): {'; '.join(case['mutation'])[:400]}\n"
            f"# class {case['class']}: {case['detail'][:300]}\n"
            f"B=${{BALLISTA:-{shlex.quote(b)}}}\ncd \"$(dirname \"$0\")\" && rm -rf out\n")
    if plan["mode"] == "sequential":
        body = f"{q(plan['first'])}; echo \"first exit $?\"\n{q(plan['second'])}; echo \"second exit $?\"\n"
    else:
        ck = " || [ ! -d out/checkpoints ]" if plan["variant"] == "restart" else ""
        hold = "kill -STOP $A\n" if plan["mode"] == "paused" else f"sleep {plan['delay']}\n"
        body = (f"{q(plan['first'])} > a.log 2>&1 &\nA=$!\n"
                f"while {{ [ ! -e out/particles_000000.h5 ]{ck}; }} && kill -0 $A 2>/dev/null; do sleep 0.01; done\n"
                f"{hold}{q(plan['second'])}; echo \"second exit $?\"\n"
                + ("kill -CONT $A\n" if plan["mode"] == "paused" else "")
                + "wait $A; echo \"first exit $? (its output: a.log)\"\n")
    tools = os.path.dirname(os.path.abspath(__file__))
    return head + body + f"/usr/bin/python3 {shlex.quote(os.path.join(tools, 'fuzz_folders.py'))} check out\n"


# ---------------------------------------------------------------------------------------------
# user files in the results folder
# ---------------------------------------------------------------------------------------------
def make_userfile(rng, stem, path, case_dir, ballista, mut, examples_dir):
    _write_deck(path, case_dir)
    red = USERFILE_DECKS[stem]
    run = [ballista, "run", "deck.yaml", "-o", "out"] + COMMON + _sets(red)
    if not mut:
        return {"variant": "new_folder", "files": {}, "cmds": [["main", run, "."]]}, \
            ["baseline: a run into a new folder"]
    variant = rng.choice(["fresh", "fresh", "dot", "earlier_run", "earlier_run", "restart", "overwrite", "into_file"])
    names = rng.sample(sorted(USER_FILES), rng.choice([1, 1, 2, 4]))
    if variant in ("earlier_run", "restart") and rng.random() < 0.15:
        names.append("checkpoints/README.txt")
    if variant == "into_file" and "mydata.csv" not in names:
        names.append("mydata.csv")
    files = {n: USER_FILES.get(n, b"user notes in the checkpoints folder\n").hex() for n in names}
    cmds = []
    if variant == "fresh":
        cmds.append(["main", run, "."])
    elif variant == "overwrite":
        cmds.append(["main", run + ["--overwrite"], "."])
    elif variant == "dot":
        cmds.append(["main", [ballista, "run", "../deck.yaml", "-o", "."] + COMMON + _sets(red), "out"])
    elif variant == "into_file":
        cmds.append(["main", [ballista, "run", "deck.yaml", "-o", "out/mydata.csv"] + COMMON + _sets(red), "."])
    elif variant == "earlier_run":
        cmds += [["earlier", run, "."], ["main", run, "."]]
    else:
        first = run + ["--set", "output.checkpoint_interval=1.0e-6"]
        later = repr(1.5 * float(red["simulation.end_time"]))
        restart = [ballista, "run", "--restart", "out"] + COMMON + ["--set", f"simulation.end_time={later}"]
        cmds += [["earlier", first, "."], ["main", restart, "."]]
    desc = f"{variant}: user files {', '.join(names)} in the results folder" + \
        (" (added after an earlier run)" if variant in ("earlier_run", "restart") else "")
    return {"variant": variant, "files": files, "cmds": cmds}, [desc]


def _put_files(folder, files):
    for n, hexdata in files.items():
        p = os.path.join(folder, n)
        os.makedirs(os.path.dirname(p), exist_ok=True)
        with open(p, "wb") as f:
            f.write(bytes.fromhex(hexdata))


def _file_problems(folder, files):
    probs = []
    for n, hexdata in files.items():
        p = os.path.join(folder, n)
        try:
            with open(p, "rb") as f:
                if hashlib.sha256(f.read()).digest() != hashlib.sha256(bytes.fromhex(hexdata)).digest():
                    probs.append(f"{n} changed")
        except IsADirectoryError:
            probs.append(f"{n} replaced by a folder")
        except OSError:
            probs.append(f"{n} deleted")
    return probs


def execute_userfile(case, case_dir, a, rn):
    plan = case["plan"]
    folder = os.path.join(case_dir, "out")
    if plan["variant"] not in ("earlier_run", "restart", "new_folder"):
        _put_files(folder, plan["files"])
    total = 0.0
    res = None
    for tag, cmd, cwd in plan["cmds"]:
        res, _ = rn.run_cmd(cmd, os.path.join(case_dir, cwd), a, tag + ".", case_dir, folder)
        total += res["wall"]
        if tag == "earlier":
            if res["class"] != "ok":
                return dict(res, wall=round(total, 3), **{
                    "class": "baseline_failed" if res["class"] == "rejected" else res["class"],
                    "detail": f"the earlier run: {res['detail']} {res['message']}"[:1000]})
            _put_files(folder, plan["files"])
        case["cmd"] = cmd
    res["wall"] = round(total, 3)
    probs = _file_problems(folder, plan["files"])
    if probs:
        return dict(res, **{"class": "user_file_deleted",
                            "detail": (f"after a run that exited {res['exit']}: " + "; ".join(probs))[:1000]})
    return res


def repro_userfile(case, case_dir, b):
    plan = case["plan"]
    tools = os.path.dirname(os.path.abspath(__file__))
    lines = [f"#!/bin/sh\n# fuzz case {case['index']} ({case['source']}): {'; '.join(case['mutation'])[:400]}",
             f"# class {case['class']}: {case['detail'][:300]}",
             f"B=${{BALLISTA:-{shlex.quote(b)}}}", "cd \"$(dirname \"$0\")\" && rm -rf out"]
    put = "mkdir -p out && cp -r userfiles/. out/"
    if plan["variant"] not in ("earlier_run", "restart", "new_folder"):
        lines.append(put)
    for tag, cmd, cwd in plan["cmds"]:
        c = "\"$B\" " + " ".join(shlex.quote(x) for x in cmd[1:])
        lines.append(f"(cd {shlex.quote(cwd)} && {c}); echo \"{tag} run: exit $?\"")
        if tag == "earlier":
            lines.append(put)
    lines.append(f"/usr/bin/python3 {shlex.quote(os.path.join(tools, 'fuzz_folders.py'))} userfiles userfiles out")
    return "\n".join(lines) + "\n"


def keep_userfiles(case, case_dir):
    """A failing userfile case keeps the user files (userfiles/) for repro.sh."""
    _put_files(os.path.join(case_dir, "userfiles"), case["plan"]["files"])


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "check":
        p = folder_problems(sys.argv[2])
        print("\n".join(p) if p else "consistent folder")
        sys.exit(1 if p else 0)
    if len(sys.argv) == 4 and sys.argv[1] == "userfiles":
        orig, folder = sys.argv[2], sys.argv[3]
        files = {}
        for root, _, names in os.walk(orig):
            for n in names:
                with open(os.path.join(root, n), "rb") as f:
                    files[os.path.relpath(os.path.join(root, n), orig)] = f.read().hex()
        p = _file_problems(folder, files)
        print("\n".join(p) if p else f"all {len(files)} user files intact")
        sys.exit(1 if p else 0)
    sys.exit("usage: fuzz_folders.py check DIR | userfiles ORIG_DIR DIR")
