#!/usr/bin/python3
"""The V&V report: `ballista validate` runs the problems of data/validation_catalogue.yaml at one
level, checks each number against its reference's bound, and writes DIR/validate.json and one
self-contained DIR/report.html (figures embedded), the document a reviewer reads: per problem the
reference, Ballista's numbers, the bounds, pass or fail, the wall time, and the commit built.

Usage: validate.py --ballista BIN --catalogue FILE --root DIR -o OUT [--level quick|full]
                   [--only ID ...] [--skip ID ...] [--list] [--threads N]
  --root   where the catalogue's decks and scripts are (the data directory: the source tree or
           <prefix>/share/ballista)
Exit status: 0 every problem run passed, 1 a check failed or a run failed, 2 bad usage.
Run with the interpreter CMake found (BALLISTA_PYTHON, /usr/bin/python3); needs numpy, matplotlib,
PyYAML.
"""
import argparse
import base64
import csv
import html
import io
import json
import os
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import yaml

LEVELS = ("quick", "full")


def load_catalogue(path):
    with open(path, encoding="utf-8") as f:
        doc = yaml.safe_load(f)
    problems = doc.get("problems") if isinstance(doc, dict) else None
    if not isinstance(problems, list):
        raise SystemExit(f"validate: {path}: expected a top-level 'problems' list")
    ids = set()
    for k, p in enumerate(problems):
        where = f"{path}: problems.{k}"
        for key in ("id", "title", "kind", "checks", "levels"):
            if key not in p:
                raise SystemExit(f"validate: {where}: missing '{key}'")
        if p["id"] in ids:
            raise SystemExit(f"validate: {where}: duplicate id '{p['id']}'")
        ids.add(p["id"])
        if p["kind"] not in ("run", "verify", "script", "gtest"):
            raise SystemExit(f"validate: {where}.kind: expected run, verify, script or gtest, got '{p['kind']}'")
        for level in p["levels"]:
            if level not in LEVELS:
                raise SystemExit(f"validate: {where}.levels: unknown level '{level}' (quick, full)")
    return problems


def dotted(tree, path):
    """tree['a']['b'] for path 'a.b', or the quotient of two such paths for 'a.b / c.d'; None if
    absent."""
    if " / " in path:
        num, den = (dotted(tree, part.strip()) for part in path.split(" / ", 1))
        ok = isinstance(num, (int, float)) and isinstance(den, (int, float)) and den != 0
        return num / den if ok else None
    node = tree
    for part in path.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def judge(check, raw, level):
    """(display value, status, bounds) of one check; the level's entry overrides its bounds."""
    bounds = dict(check)
    bounds.update(check.get(level, {}) or {})
    if raw is None or not isinstance(raw, (int, float)):
        return None, "fail", bounds
    value = float(raw) * float(check.get("scale", 1.0))
    ok = value == value  # not NaN
    if "min" in bounds:
        ok = ok and value >= float(bounds["min"])
    if "max" in bounds:
        ok = ok and value <= float(bounds["max"])
    return value, "pass" if ok else "fail", bounds


def run_command(cmd, log_path, env=None):
    t0 = time.monotonic()
    with open(log_path, "w", encoding="utf-8") as log:
        log.write("$ " + " ".join(cmd) + "\n")
        log.flush()
        rc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env).returncode
    return rc, time.monotonic() - t0


def tail(path, lines=15):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError:
        return ""


def history_figure(run_dir, problem, results):
    """PNG (bytes) of the checked probes against time from history.csv, with the bound and the
    reference's range drawn at the end time, where they hold."""
    names = problem.get("history") or []
    path = os.path.join(run_dir, "history.csv")
    if not names or not os.path.exists(path):
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    t = [float(r["time"]) * 1e6 for r in rows]
    fig, axes = plt.subplots(1, len(names), figsize=(4.2 * len(names), 3.2), squeeze=False)
    for ax, name in zip(axes[0], names):
        check = next((c for c in problem["checks"] if c["path"] == f"probes.{name}"), {})
        scale = float(check.get("scale", 1.0))
        y = [float(r[name]) * scale if r.get(name) not in (None, "") else float("nan") for r in rows]
        ax.plot(t, y, color="C0", lw=1.5, label="Ballista")
        # The bound and the reference's range hold at the end time: drawn there, as bars.
        res = next((r for r in results if r["path"] == f"probes.{name}"), None)
        t_end = t[-1]
        ref = check.get("reference_range")
        if ref:
            ax.errorbar([t_end * 1.02], [0.5 * (ref[0] + ref[1])], yerr=[[0.5 * (ref[1] - ref[0])]],
                        color="C1", lw=3, capsize=4, fmt="none", label="reference")
        if res is not None:
            lo, hi = res["bounds"].get("min"), res["bounds"].get("max")
            if lo is not None and hi is not None and hi >= lo:
                ax.errorbar([t_end * 1.04], [0.5 * (lo + hi)], yerr=[[0.5 * (hi - lo)]], color="green", lw=1.2,
                            capsize=5, fmt="none", label="bound")
            else:
                for b in (lo, hi):
                    if b is not None:
                        ax.axhline(float(b), color="green", lw=0.8, ls="--", label="bound")
            if res["value"] is not None:
                ax.plot([t_end], [res["value"]], "o", color="C0", ms=5)
        ax.set_xlabel("t (µs)")
        ax.set_ylabel(f"{check.get('label', name)} ({check.get('unit', 'SI')})")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    plt.close(fig)
    return buf.getvalue()


def run_problem(p, args, level):
    out = os.path.join(args.output, p["id"])
    os.makedirs(out, exist_ok=True)
    spec = p["levels"][level] or {}
    log = os.path.join(out, "log.txt")
    record = {"id": p["id"], "title": p["title"], "section": p.get("section", ""),
              "reference": p.get("reference", ""), "kind": p["kind"], "level": level, "checks": [],
              "command": None, "wall_seconds": None, "status": "fail", "message": ""}
    env = dict(os.environ)
    if args.threads:
        env["OMP_NUM_THREADS"] = str(args.threads)
    if p["kind"] == "run":
        deck = os.path.join(args.root, p["deck"])
        cmd = [args.ballista, "run", deck, "-o", os.path.join(out, "run"), "--quiet"]
        if args.threads:
            cmd += ["--threads", str(args.threads)]
        for s in spec.get("set", []) + p.get("set", []):
            cmd += ["--set", s]
        result_file = os.path.join(out, "run", "summary.json")
    elif p["kind"] == "verify":
        cmd = [args.ballista, "verify", "-o", os.path.join(out, "verify"), "--quiet"] + list(spec.get("args", []))
        result_file = os.path.join(out, "verify", "verify.json")
    elif p["kind"] == "gtest":
        exe = os.path.join(os.path.dirname(os.path.abspath(args.ballista)), p["executable"])
        if not os.path.exists(exe):
            record.update(status="not run", message=f"{p['executable']} is in the build tree only (cmake --build "
                          f"build --target {os.path.basename(p['executable'])})")
            return record
        xml_path = os.path.join(out, "gtest.xml")
        cmd = [exe, f"--gtest_filter={spec.get('filter', p.get('filter', '*'))}", f"--gtest_output=xml:{xml_path}"]
        result_file = None
    else:
        script = os.path.join(args.root, p["script"])
        if not os.path.exists(script):
            record.update(status="not run", message=f"{p['script']} is in the source tree only")
            return record
        subst = {"ballista": args.ballista, "out": os.path.join(out, "run")}
        cmd = [sys.executable, script] + [a.format(**subst) for a in spec.get("args", [])]
        result_file = os.path.join(out, "run", p["result"]) if p.get("result") else None
    record["command"] = " ".join(cmd)
    rc, wall = run_command(cmd, log, env)
    record["wall_seconds"] = wall
    tree = {}
    if result_file and os.path.exists(result_file):
        with open(result_file, encoding="utf-8") as f:
            tree = json.load(f)
        if p["kind"] == "verify":
            s = tree.get("summary", {})
            tree = {"passed": s.get("pass"), "failed": s.get("fail"), "not_applicable": s.get("not_applicable")}
    post = p.get("post")
    if post and p["kind"] == "run" and rc == 0:
        # A script of validation/ that reads the run's folder and writes its numbers as JSON
        # (checks read them under "post."); from the source tree only.
        script = os.path.join(args.root, post["script"])
        if not os.path.exists(script):
            record.update(status="not run", message=f"{post['script']} is in the source tree only")
            return record
        run_dir = os.path.join(out, "run")
        post_json = os.path.join(out, "post.json")
        subst = {"run": run_dir, "result": post_json}
        prc, _ = run_command([sys.executable, script] + [a.format(**subst) for a in post.get("args", [])],
                             os.path.join(out, "post_log.txt"), env)
        if prc == 0 and os.path.exists(post_json):
            with open(post_json, encoding="utf-8") as f:
                tree["post"] = json.load(f)
        else:
            rc = prc
            log = os.path.join(out, "post_log.txt")
    if p["kind"] == "gtest" and os.path.exists(xml_path):
        record["tests"] = gtest_results(xml_path)
        tree = {"passed": sum(t["status"] == "pass" for t in record["tests"]),
                "failed": sum(t["status"] == "fail" for t in record["tests"])}
    # A verify run or a test executable exits 1 when a test fails: the checks say so; any other
    # non-zero exit is a run that did not finish.
    finished = rc == 0 or (p["kind"] in ("verify", "gtest") and rc == 1 and tree)
    for c in p["checks"]:
        value, status, bounds = judge(c, dotted(tree, c["path"]), level)
        record["checks"].append({"label": c["label"], "path": c["path"], "unit": c.get("unit", ""),
                                 "value": value, "status": status, "why": bounds.get("why", ""),
                                 "bounds": {k: bounds[k] for k in ("min", "max") if k in bounds}})
    if not finished:
        record["message"] = f"exit status {rc}; the end of its log:\n" + tail(log)
        return record
    record["status"] = "pass" if all(c["status"] == "pass" for c in record["checks"]) else "fail"
    # A documented difference from the reference (its cause in docs/validation.md) is reported as
    # such and does not fail the report; if it ever passes, the report says so.
    if p.get("known_gap"):
        record["known_gap"] = p["known_gap"]
        if record["status"] == "fail":
            record["status"] = "known gap"
    png = None
    if p["kind"] == "run":
        try:
            png = history_figure(os.path.join(out, "run"), p, record["checks"])
        except Exception as err:  # a figure that cannot be drawn does not lose the numbers
            record["message"] = f"figure not drawn: {err}"
    elif p.get("figure") and os.path.exists(os.path.join(out, "run", p["figure"])):
        with open(os.path.join(out, "run", p["figure"]), "rb") as f:
            png = f.read()
    if png:
        record["figure_png_base64"] = base64.b64encode(png).decode("ascii")
    return record


def gtest_results(path):
    """Each test case of a gtest XML report: name, status, time and the numbers it recorded
    (tests/verification/verification_support.hpp, report())."""
    tests = []
    for case in ET.parse(path).getroot().iter("testcase"):
        if case.get("result") == "skipped" or case.get("status") == "notrun":
            continue
        props = {p.get("name"): p.get("value") for p in case.iter("property")}
        failure = case.find("failure")
        tests.append({"name": f"{case.get('classname')}.{case.get('name')}",
                      "status": "fail" if failure is not None else "pass",
                      "seconds": float(case.get("time", "0")), "properties": props,
                      "failure": (failure.get("message") or "")[:2000] if failure is not None else ""})
    return tests


def fmt_value(v):
    if v is None:
        return "missing"
    return f"{v:.4g}"


def fmt_bounds(b):
    lo, hi = b.get("min"), b.get("max")
    if lo is not None and hi is not None:
        return f"[{lo:g}, {hi:g}]"
    if lo is not None:
        return f"≥ {lo:g}"
    if hi is not None:
        return f"≤ {hi:g}"
    return "—"


def write_report(path, records, info):
    e = html.escape
    n_pass = sum(r["status"] == "pass" for r in records)
    n_fail = sum(r["status"] == "fail" for r in records)
    n_skip = sum(r["status"] == "not run" for r in records)
    n_gap = sum(r["status"] == "known gap" for r in records)
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'><title>Ballista V&amp;V report</title>",
        "<style>body{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}"
        "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}"
        ".pass{color:#070}.fail{color:#b00;font-weight:bold}.gap{color:#b60;font-weight:bold}.skip{color:#777}pre{background:#f4f4f4;padding:6px;"
        "white-space:pre-wrap}</style></head><body>",
        "<h1>Ballista verification and validation report</h1>",
        f"<p>{e(info['version'])}; level <b>{e(info['level'])}</b>; {e(info['date'])}; "
        f"{info['wall_seconds']:.1f} s in all. Catalogue: {e(info['catalogue'])}.</p>",
        f"<p><b>{n_pass} passed, {n_fail} failed, {n_gap} known gaps, {n_skip} not run</b> of {len(records)} problems. "
        "The bounds and the references are those of docs/validation.md; a quick-level run is at CI size, "
        "so its numbers are not converged (docs/validation.md gives each problem's resolution study).</p>",
        "<table><tr><th>problem</th><th>status</th><th>wall (s)</th></tr>",
    ]
    for r in records:
        cls = {"pass": "pass", "fail": "fail", "known gap": "gap"}.get(r["status"], "skip")
        wall = "" if r["wall_seconds"] is None else f"{r['wall_seconds']:.1f}"
        parts.append(f"<tr><td><a href='#{e(r['id'])}'>{e(r['title'])}</a></td>"
                     f"<td class='{cls}'>{e(r['status'])}</td><td>{wall}</td></tr>")
    parts.append("</table>")
    for r in records:
        cls = {"pass": "pass", "fail": "fail", "known gap": "gap"}.get(r["status"], "skip")
        parts.append(f"<h2 id='{e(r['id'])}'>{e(r['title'])} — <span class='{cls}'>{e(r['status'])}</span></h2>")
        parts.append(f"<p>docs/validation.md: {e(r['section'])}. Reference: {e(r['reference'])}.</p>")
        if r.get("known_gap"):
            verdict = "still open" if r["status"] == "known gap" else "this run now meets the bounds"
            parts.append(f"<p class='gap'>Known gap ({verdict}): {e(r['known_gap'])}</p>")
        if r["command"]:
            parts.append(f"<p>Command ({r['wall_seconds']:.1f} s):</p><pre>{e(r['command'])}</pre>")
        parts.append("<table><tr><th>quantity</th><th>Ballista</th><th>unit</th><th>bound</th><th>status</th>"
                     "<th>why this bound</th></tr>")
        for c in r["checks"]:
            ccls = "pass" if c["status"] == "pass" else "fail"
            parts.append(f"<tr><td>{e(c['label'])}</td><td>{fmt_value(c['value'])}</td><td>{e(c['unit'])}</td>"
                         f"<td>{e(fmt_bounds(c['bounds']))}</td><td class='{ccls}'>{e(c['status'])}</td>"
                         f"<td>{e(c['why'])}</td></tr>")
        parts.append("</table>")
        if r.get("tests"):
            parts.append("<table><tr><th>test (its own assertions, tolerances justified in its source)</th>"
                         "<th>status</th><th>s</th><th>numbers it recorded</th></tr>")
            for t in r["tests"]:
                tcls = "pass" if t["status"] == "pass" else "fail"
                props = "; ".join(f"{k} = {v}" for k, v in t["properties"].items())
                extra = f"<pre>{e(t['failure'])}</pre>" if t["failure"] else ""
                parts.append(f"<tr><td>{e(t['name'])}</td><td class='{tcls}'>{e(t['status'])}</td>"
                             f"<td>{t['seconds']:.1f}</td><td>{e(props)}{extra}</td></tr>")
            parts.append("</table>")
        if r.get("message"):
            parts.append(f"<pre>{e(r['message'])}</pre>")
        if r.get("figure_png_base64"):
            parts.append(f"<img alt='{e(r['id'])}' src='data:image/png;base64,{r['figure_png_base64']}'>")
        if r["kind"] == "verify" and os.path.exists(os.path.join(info["output"], r["id"], "verify", "report.html")):
            parts.append(f"<p>Per test and model: <a href='{e(r['id'])}/verify/report.html'>the suite's own "
                         "report</a> (written when the suite ran with its figures).</p>")
    parts.append("</body></html>")
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write("\n".join(parts))
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ballista", required=True)
    ap.add_argument("--catalogue", required=True)
    ap.add_argument("--root", required=True)
    ap.add_argument("-o", "--output", default="out/validate")
    ap.add_argument("--level", choices=LEVELS, default="quick")
    ap.add_argument("--only", action="append", default=[])
    ap.add_argument("--skip", action="append", default=[])
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--threads", type=int, default=0)
    args = ap.parse_args()
    problems = load_catalogue(args.catalogue)
    known = {p["id"] for p in problems}
    for flag, names in (("--only", args.only), ("--skip", args.skip)):
        for name in names:
            if name not in known:
                ap.error(f"{flag} {name}: no such problem (known: {', '.join(sorted(known))})")
    chosen = [p for p in problems if (not args.only or p["id"] in args.only) and p["id"] not in args.skip
              and args.level in p["levels"]]
    if args.list:
        for p in problems:
            print(f"{p['id']:<20} {'/'.join(l for l in LEVELS if l in p['levels']):<11} {p['title']}")
        return 0
    os.makedirs(args.output, exist_ok=True)
    version = subprocess.run([args.ballista, "--version"], capture_output=True, text=True).stdout.strip()
    t0 = time.monotonic()
    records = []
    for p in chosen:
        r = run_problem(p, args, args.level)
        records.append(r)
        mark = {"pass": "pass", "fail": "FAIL", "known gap": "gap"}.get(r["status"], r["status"])
        summary = "; ".join(f"{c['label']} {fmt_value(c['value'])} {c['unit']} {fmt_bounds(c['bounds'])}"
                            for c in r["checks"])
        wall = "" if r["wall_seconds"] is None else f" ({r['wall_seconds']:.1f} s)"
        print(f"{p['id']:<20} {mark:<7}{wall} {summary}", flush=True)
    info = {"version": version or "ballista (version unknown)", "level": args.level,
            "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "wall_seconds": time.monotonic() - t0,
            "catalogue": os.path.abspath(args.catalogue), "output": args.output}
    with open(os.path.join(args.output, "validate.json"), "w", encoding="utf-8") as f:
        json.dump({"info": info, "problems": [{k: v for k, v in r.items() if k != "figure_png_base64"}
                                              for r in records]}, f, indent=1)
    report = os.path.join(args.output, "report.html")
    write_report(report, records, info)
    n_fail = sum(r["status"] == "fail" for r in records)
    n_gap = sum(r["status"] == "known gap" for r in records)
    n_pass = sum(r["status"] == "pass" for r in records)
    print(f"validate: {n_pass} of {len(records)} problems passed at level {args.level}, {n_fail} failed, "
          f"{n_gap} known gaps; report {os.path.abspath(report)}")
    return 1 if n_fail else 0


if __name__ == "__main__":
    sys.exit(main())
