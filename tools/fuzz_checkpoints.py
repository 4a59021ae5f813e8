"""Checkpoint cases of the fuzz harness (tools/fuzz_decks.py; issue 35): checkpoint:<stem>.

A small deck runs at its reduced size to a short end time T1 with output.checkpoint_interval
(T1/4, keep 3: three checkpoints). A copy of that folder is restarted with a later end time T2
(`ballista run --restart REF --set simulation.end_time=T2`): the reference. Another copy is
damaged and restarted the same way:
  bitflip   1, 10 or 2000 bits flipped at random offsets of the newest checkpoint (sometimes of
            every checkpoint);
  truncate  the newest checkpoint cut at a random byte;
  swap      the names of two checkpoint files exchanged;
  foreign   a checkpoint of another run (the same deck with another CFL number, or another deck)
            copied in under a newer name or over the newest;
  empty     an empty (or garbage) file named like a checkpoint, newest or over the newest;
  delete    every checkpoint deleted (or the checkpoints folder).
Outcomes: a non-zero exit with a message is `rejected`; exit 0 with the reference's results
(summary.json less timing entries, the `restarted_from` path and warnings, and history.csv, byte
for byte) is `ok` (a fallback to an older checkpoint gives the same results: the run is
deterministic); exit 0 with other results is `corrupt_checkpoint_accepted`. The unmutated case
(--baseline) restarts an undamaged copy, which must give the reference.

Every command runs with the case folder as working directory and relative paths, so the
checkpoints (which store the deck's file name) have the same bytes wherever --out is. The damaged
folder is kept as `damaged/` in a failing case's folder; repro.sh restarts a copy of it and compares
with `reference/` (`python3 tools/fuzz_checkpoints.py compare reference restart`).
"""
import json
import os
import random
import shlex
import shutil
import sys

# deck -> (reduction --set, T1, T2)
DECKS = {
    "taylor_bar_mpm": ({"grid.cell_size": "0.8e-3"}, 10e-6, 15e-6),
    "pd_kalthoff_winkler": ({"grid.cell_size": "2.0e-3"}, 10e-6, 15e-6),
    "taylor_bar_otm": ({"grid.cell_size": "0.8e-3"}, 8e-6, 12e-6),
    "explosive_sandwich_mpm": ({"grid.cell_size": "1.0e-3"}, 4e-6, 6e-6),
    "exploding_cylinder_pd": ({"grid.cell_size": "1.72e-3", "bodies.1.point_spacing": "3.44e-3"}, 2e-6, 3e-6),
}
FOREIGN_DECK = "taylor_bar_mpm"
OPS = ["bitflip", "bitflip", "bitflip", "truncate", "swap", "foreign", "empty", "delete"]
# summary.json keys that differ between two runs of the same state (or name the folder)
VOLATILE = {"restarted_from", "timing", "wall_time", "particle_steps_per_second", "warnings"}
COMMON = ["--no-plots", "-q", "--threads", "1"]


def _sets(d):
    out = []
    for k, v in d.items():
        out += ["--set", f"{k}={v}"]
    return out


def make(rng, stem, path, case_dir, ballista, mut, examples_dir):
    """Write the deck(s) into case_dir and plan the case (no command runs here)."""
    red, t1, t2 = DECKS[stem]
    with open(path, "rb") as f:
        data = f.read()
    with open(os.path.join(case_dir, "deck.yaml"), "wb") as f:
        f.write(data)
    first = [ballista, "run", "deck.yaml", "-o", "run"] + COMMON + _sets(red) + _sets({
        "simulation.end_time": repr(t1), "output.checkpoint_interval": repr(t1 / 4), "output.checkpoint_keep": "3"})
    restart = COMMON + ["--set", f"simulation.end_time={t2!r}"]
    plan = {"first": first, "restart": restart, "op": None, "mutation": []}
    if not mut:
        return plan
    op = rng.choice(OPS)
    plan["op"] = op
    plan["op_seed"] = rng.randrange(1 << 30)
    if op == "bitflip":
        plan["bits"] = rng.choice([1, 1, 10, 10, 2000])
        plan["all"] = rng.random() < 0.1
        plan["mutation"] = [f"{plan['bits']} bit(s) flipped at random offsets of "
                            f"{'every checkpoint' if plan['all'] else 'the newest checkpoint'}"]
    elif op == "truncate":
        plan["mutation"] = ["the newest checkpoint truncated at a random byte"]
    elif op == "swap":
        plan["mutation"] = ["the names of two checkpoint files swapped"]
    elif op == "foreign":
        other = rng.random() < 0.5 and stem != FOREIGN_DECK
        fstem = FOREIGN_DECK if other else stem
        fred, ft1, _ = DECKS[fstem]
        with open(os.path.join(examples_dir, fstem + ".yaml"), "rb") as f:
            fdata = f.read()
        with open(os.path.join(case_dir, "foreign.yaml"), "wb") as f:
            f.write(fdata)
        extra = {} if other else {"simulation.cfl": rng.choice(["0.2", "0.25"]) if "otm" not in stem else "0.7"}
        if "_pd" in stem or stem.startswith("pd_"):
            extra = {} if other else {"peridynamics.dt_safety": "0.6"}
        plan["foreign"] = [ballista, "run", "foreign.yaml", "-o", "foreign"] + COMMON + _sets(fred) + _sets(dict(
            {"simulation.end_time": repr(ft1), "output.checkpoint_interval": repr(ft1 / 4),
             "output.checkpoint_keep": "3"}, **extra))
        plan["foreign_over"] = rng.random() < 0.3
        plan["mutation"] = [f"a checkpoint of another run ({fstem}{' ' + str(extra) if extra else ''}) "
                            f"{'over the newest' if plan['foreign_over'] else 'under a newer name'}"]
    elif op == "empty":
        plan["garbage"] = rng.random() < 0.3
        plan["empty_over"] = rng.random() < 0.4
        plan["mutation"] = [f"{'a garbage' if plan['garbage'] else 'an empty'} file named like a checkpoint "
                            f"{'over the newest' if plan['empty_over'] else '(newest name)'}"]
    else:
        plan["whole_dir"] = rng.random() < 0.3
        plan["mutation"] = ["the checkpoints folder deleted" if plan["whole_dir"] else "every checkpoint deleted"]
    return plan


def _checkpoints(folder):
    d = os.path.join(folder, "checkpoints")
    if not os.path.isdir(d):
        return []
    return sorted(os.path.join(d, n) for n in os.listdir(d) if n.startswith("checkpoint_") and n.endswith(".h5"))


def _name(step):
    return f"checkpoint_{step:012d}.h5"


def _step(path):
    try:
        return int(os.path.basename(path)[len("checkpoint_"):-3])
    except ValueError:
        return 0


def damage(plan, folder, case_dir, rng):
    """Apply the planned damage to folder; returns a description of exactly what was done."""
    cks = _checkpoints(folder)
    op = plan["op"]
    newest = cks[-1]
    if op == "bitflip":
        done = []
        for ck in (cks if plan["all"] else [newest]):
            with open(ck, "rb") as f:
                b = bytearray(f.read())
            offs = sorted(rng.sample(range(len(b) * 8), min(plan["bits"], len(b) * 8)))
            for o in offs:
                b[o // 8] ^= 1 << (o % 8)
            with open(ck, "wb") as f:
                f.write(b)
            shown = ", ".join(str(o) for o in offs[:10]) + (" ..." if len(offs) > 10 else "")
            done.append(f"{os.path.basename(ck)}: bits {shown}")
        return "; ".join(done)
    if op == "truncate":
        n = rng.randrange(os.path.getsize(newest))
        with open(newest, "r+b") as f:
            f.truncate(n)
        return f"{os.path.basename(newest)} truncated to {n} bytes"
    if op == "swap":
        a, b = (newest, rng.choice(cks[:-1])) if rng.random() < 0.7 else tuple(rng.sample(cks, 2))
        tmp = a + ".swap"
        os.rename(a, tmp)
        os.rename(b, a)
        os.rename(tmp, b)
        return f"{os.path.basename(a)} <-> {os.path.basename(b)}"
    if op == "foreign":
        src = _checkpoints(os.path.join(case_dir, "foreign"))[-1]
        dst = newest if plan["foreign_over"] else os.path.join(os.path.dirname(newest),
                                                                 _name(max(_step(newest), _step(src)) + 1))
        shutil.copyfile(src, dst)
        return f"{os.path.relpath(src, case_dir)} copied to {os.path.basename(dst)}"
    if op == "empty":
        dst = newest if plan["empty_over"] else os.path.join(os.path.dirname(newest), _name(_step(newest) + 1))
        with open(dst, "wb") as f:
            f.write(bytes(rng.randrange(256) for _ in range(rng.choice([1, 100, 5000]))) if plan["garbage"] else b"")
        return f"{os.path.basename(dst)} {'garbage' if plan['garbage'] else 'empty'}"
    if plan["whole_dir"]:
        shutil.rmtree(os.path.join(folder, "checkpoints"))
        return "checkpoints/ deleted"
    for ck in cks:
        os.remove(ck)
    return f"{len(cks)} checkpoints deleted"


def _strip(node):
    if isinstance(node, dict):
        return {k: _strip(v) for k, v in node.items()
                if k not in VOLATILE and "seconds" not in k and "wall" not in k}
    if isinstance(node, list):
        return [_strip(v) for v in node]
    return node


def compare(ref, got):
    """Differences between two restarted folders' results ([] when equal)."""
    diffs = []
    try:
        with open(os.path.join(ref, "summary.json")) as f:
            a = _strip(json.load(f))
        with open(os.path.join(got, "summary.json")) as f:
            b = _strip(json.load(f))
    except (OSError, ValueError) as e:
        return [f"summary.json unreadable: {e}"]

    def walk(x, y, path):
        if len(diffs) >= 5:
            return
        if isinstance(x, dict) and isinstance(y, dict):
            for k in list(x) + [k for k in y if k not in x]:
                if k not in x or k not in y:
                    diffs.append(f"{path}.{k} only in {'the reference' if k in x else 'the restart'}")
                else:
                    walk(x[k], y[k], f"{path}.{k}")
        elif x != y:
            diffs.append(f"{path}: {json.dumps(x)[:80]} (reference) vs {json.dumps(y)[:80]}")
    walk(a, b, "summary")
    try:
        with open(os.path.join(ref, "history.csv")) as f:
            ha = f.read().splitlines()
        with open(os.path.join(got, "history.csv")) as f:
            hb = f.read().splitlines()
    except OSError as e:
        return diffs + [f"history.csv unreadable: {e}"]
    if ha != hb:
        n = next((i for i in range(min(len(ha), len(hb))) if ha[i] != hb[i]), min(len(ha), len(hb)))
        diffs.append(f"history.csv differs from row {n} ({len(ha)} rows in the reference, {len(hb)} in the restart)")
    return diffs


def execute(case, case_dir, a, rn):
    """Run the case (first run, reference restart, damage, restart) and classify it."""
    plan = case["plan"]
    rng = random.Random(plan.get("op_seed", 0))
    b = case["cmd"][0]
    total = 0.0

    def step(cmd, tag, out):
        nonlocal total
        res, raw = rn.run_cmd(cmd, case_dir, a, tag, case_dir, os.path.join(case_dir, out))
        total += res["wall"]
        return res, raw

    def fail(res, what):
        res = dict(res)
        res["detail"] = f"{what}: {res['detail']} {res['message']}"[:1000]
        res["wall"] = round(total, 3)
        return res
    res, _ = step(plan["first"], "first.", "run")
    if res["class"] != "ok":
        return fail(res if res["class"] != "rejected" else dict(res, **{"class": "baseline_failed"}),
                    "the undamaged first run")
    if len(_checkpoints(os.path.join(case_dir, "run"))) < 2:
        return fail(dict(res, **{"class": "baseline_failed", "detail": "fewer than 2 checkpoints"}), "first run")
    shutil.copytree(os.path.join(case_dir, "run"), os.path.join(case_dir, "reference"))
    res, _ = step([b, "run", "--restart", "reference"] + plan["restart"], "reference.", "reference")
    if res["class"] != "ok":
        return fail(res if res["class"] != "rejected" else dict(res, **{"class": "baseline_failed"}),
                    "the reference restart of the undamaged folder")
    shutil.copytree(os.path.join(case_dir, "run"), os.path.join(case_dir, "damaged"))
    done = "none (undamaged copy)"
    if plan["op"]:
        if plan["op"] == "foreign":
            fres, _ = step(plan["foreign"], "foreign.", "foreign")
            if fres["class"] != "ok" or not _checkpoints(os.path.join(case_dir, "foreign")):
                return fail(dict(fres, **{"class": "baseline_failed"}), "the foreign run")
        done = damage(plan, os.path.join(case_dir, "damaged"), case_dir, rng)
    case["mutation"] = case["mutation"] + [f"done: {done}"]
    shutil.copytree(os.path.join(case_dir, "damaged"), os.path.join(case_dir, "restart"))
    cmd = [b, "run", "--restart", "restart"] + plan["restart"]
    case["cmd"] = cmd
    res, _ = step(cmd, "", "restart")
    res["wall"] = round(total, 3)
    if res["class"] in ("ok", "ignored_input"):
        diffs = compare(os.path.join(case_dir, "reference"), os.path.join(case_dir, "restart"))
        if diffs:
            res["class"] = "corrupt_checkpoint_accepted"
            res["detail"] = ("exit 0 with results other than the reference restart's: " + "; ".join(diffs))[:1000]
    elif res["class"] == "nonfinite_success":
        res["class"] = "corrupt_checkpoint_accepted"
        res["detail"] = ("exit 0 with non-finite results: " + res["detail"])[:1000]
    return res


def cleanup_kept(case_dir):
    """A failing case keeps damaged/ (the restart's input), reference/ and restart/ results; the
    particle files are dropped (a restart does not read them), the checkpoints of damaged/ stay."""
    for sub in ("run", "foreign"):
        shutil.rmtree(os.path.join(case_dir, sub), ignore_errors=True)
    for sub in ("damaged", "reference", "restart"):
        for root, dirs, names in os.walk(os.path.join(case_dir, sub)):
            for n in names:
                if n.endswith(".h5") and not (sub == "damaged" and os.path.basename(root) == "checkpoints"):
                    os.remove(os.path.join(root, n))
    shutil.rmtree(os.path.join(case_dir, "reference", "checkpoints"), ignore_errors=True)
    shutil.rmtree(os.path.join(case_dir, "restart", "checkpoints"), ignore_errors=True)


def repro(case, case_dir, tools_dir):
    plan = case["plan"]
    first = " ".join(shlex.quote(c) for c in ["\"$B\""] + plan["first"][1:]).replace("'\"$B\"'", "\"$B\"")
    rest = " ".join(shlex.quote(c) for c in plan["restart"])
    return (f"#!/bin/sh\n# fuzz case {case['index']} ({case['source']}): {'; '.join(case['mutation'])[:600]}\n"
            f"# class {case['class']}: {case['detail'][:300]}\n"
            f"# made by: {first}   (into run/), then a copy restarted as reference/, a copy damaged as damaged/\n"
            f"B=${{BALLISTA:-{shlex.quote(case['cmd'][0])}}}\n"
            "cd \"$(dirname \"$0\")\" && rm -rf restart && cp -r damaged restart\n"
            f"timeout 60 \"$B\" run --restart restart {rest}\necho \"exit $?\"\n"
            f"/usr/bin/python3 {shlex.quote(os.path.join(tools_dir, 'fuzz_checkpoints.py'))} "
            "compare reference restart\n")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "compare":
        d = compare(sys.argv[2], sys.argv[3])
        print("\n".join(d) if d else "same results as the reference")
        sys.exit(1 if d else 0)
    sys.exit("usage: fuzz_checkpoints.py compare REFERENCE_DIR RESTART_DIR")
