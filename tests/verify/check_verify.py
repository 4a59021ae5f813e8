#!/usr/bin/python3
"""Runs `ballista verify -o OUT` and checks what it produced (ctest verify.single_element_suite).

Asserts: exit status 0; OUT/verify.json parses; every test passed or is not applicable with a
reason (none failed); every model `ballista info` lists has all twelve tests (A1, A2, A2-iso, A2-kin,
A3, A4, A5, A5-fluid, A6-objectivity, A6-tangent, A7, A8) and passed A6-objectivity (CATALOGUE A6
applies to every model); A3-A5 and A8 are not applicable only with a reason naming the hook
(reduce_geo);
every test with a plot has a PNG; OUT/report.html exists and embeds one PNG per plotted test (a
data: URI: the page is self-contained). Then, with BALLISTA_PYTHON pointing at a missing interpreter and at one without
matplotlib: exit status 4, a message naming the interpreter and matplotlib, verify.json written.
"""
import argparse
import base64
import json
import os
import re
import shutil
import subprocess
import sys
import time

TESTS = ["A1", "A2", "A2-iso", "A2-kin", "A3", "A4", "A5", "A5-fluid", "A6-objectivity", "A6-tangent", "A7",
         "A8"]
# Tests that need MaterialFactory::reduce_geo: not applicable exactly when the model lacks it.
GEO_TESTS = ["A3", "A4", "A5", "A5-fluid", "A8"]


def fail(msg):
    sys.stderr.write("check_verify: FAIL: " + msg + "\n")
    sys.exit(1)


def registered_models(ballista):
    out = subprocess.run([ballista, "info"], capture_output=True, text=True, check=True).stdout
    part = out.split("\nMaterials (materials.<name>.model)\n", 1)
    if len(part) != 2:
        fail("`ballista info` has no Materials section")
    # The section ends at the next unindented heading (e.g. "Material presets"). Model lines are
    # indented by exactly two spaces; parameters by six.
    section = re.split(r"^\S", part[1], maxsplit=1, flags=re.M)[0]
    return [m.group(1) for m in re.finditer(r"^  (\S+)  ", section, re.M)]


def check_missing_python(a):
    """Without a usable interpreter the tests still run and verify.json is written, the command
    exits 4 and says what is missing: a non-existent BALLISTA_PYTHON, then one that cannot import
    matplotlib (a stand-in script that fails every import)."""
    out = a.out + "_nopython"
    fake = os.path.join(out, "python_without_matplotlib")
    os.makedirs(out, exist_ok=True)
    with open(fake, "w") as f:
        f.write("#!/bin/sh\nexit 1\n")
    os.chmod(fake, 0o755)
    for python, expect in [("/nonexistent/python3", "does not exist"), (fake, "cannot import")]:
        env = dict(os.environ, BALLISTA_PYTHON=python)
        r = subprocess.run([a.ballista, "verify", "-o", out, "--model", "linear_elastic", "--test", "A6-objectivity"],
                           capture_output=True, text=True, env=env)
        if r.returncode != 4:
            fail("with BALLISTA_PYTHON={}: exit status {} (expected 4)".format(python, r.returncode))
        if expect not in r.stderr or "matplotlib" not in r.stderr or python not in r.stderr:
            fail("with BALLISTA_PYTHON={}: unclear message: {}".format(python, r.stderr.strip()))
        if not os.path.isfile(os.path.join(out, "verify.json")):
            fail("with BALLISTA_PYTHON={}: no verify.json".format(python))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ballista", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    if os.path.exists(a.out):
        shutil.rmtree(a.out)
    t0 = time.time()
    r = subprocess.run([a.ballista, "verify", "-o", a.out], capture_output=True, text=True)
    secs = time.time() - t0
    sys.stdout.write(r.stdout)
    sys.stderr.write(r.stderr)
    if r.returncode != 0:
        fail("`ballista verify` exited with status {}".format(r.returncode))
    with open(os.path.join(a.out, "verify.json"), encoding="utf-8") as f:
        doc = json.load(f)
    tests = doc["tests"]
    if not tests:
        fail("verify.json lists no tests")
    for t in tests:
        name = "{} {}".format(t["model"], t["test"])
        if t["status"] == "fail" or t["status"] not in ("pass", "not_applicable"):
            fail("{}: status {} ({})".format(name, t["status"], t["reason"]))
        if t["status"] == "not_applicable" and not t["reason"]:
            fail(name + ": not applicable without a reason")
        if t["status"] == "pass":
            if t["max_rel_error"] is None or t["tolerance"] is None or not t["tolerance_justification"]:
                fail(name + ": passed without error, tolerance and justification")
            if not t["max_rel_error"] <= t["tolerance"]:
                fail(name + ": passed with max_rel_error {} > tolerance {}".format(t["max_rel_error"], t["tolerance"]))
            if not t["checks"] or not all(c["pass"] for c in t["checks"]):
                fail(name + ": passed with a failing or no check")
            if not t["plot"] or not t["series"]:
                fail(name + ": passed without plot data")
    if not doc["summary"]["all_passed"] or doc["summary"]["fail"] != 0:
        fail("summary says a test failed")
    models = registered_models(a.ballista)
    if not models:
        fail("no registered model found in `ballista info`")
    for m in models:
        have = {t["test"]: t for t in tests if t["model"] == m}
        missing = [x for x in TESTS if x not in have]
        if missing:
            fail("model {} lacks tests {}".format(m, missing))
        for x in GEO_TESTS:
            if have[x]["status"] == "not_applicable" and not re.search(r"reduce_geo", have[x]["reason"]):
                fail("model {} {}: not applicable for an unexpected reason ({})".format(m, x, have[x]["reason"]))
        if have["A6-objectivity"]["status"] != "pass":
            fail("model {}: A6-objectivity must run and pass for every model ({})".format(
                m, have["A6-objectivity"]["reason"]))
    report = os.path.join(a.out, "report.html")
    if not os.path.isfile(report):
        fail("no report.html")
    with open(report, encoding="utf-8") as f:
        page = f.read()
    images = re.findall(r"<img src='([^']+)'", page)
    plotted = [t for t in tests if t["plot"]]
    if len(images) != len(plotted):
        fail("report.html references {} images for {} tests with plots".format(len(images), len(plotted)))
    # Self-contained: every image is embedded as a data: URI holding a PNG (plots/ is a copy).
    for src in images:
        prefix = "data:image/png;base64,"
        if not src.startswith(prefix):
            fail("report.html links an image instead of embedding it: " + src[:80])
        if base64.b64decode(src[len(prefix):])[:8] != b"\x89PNG\r\n\x1a\n":
            fail("an image embedded in report.html is not a PNG")

    check_missing_python(a)
    n_pass = sum(t["status"] == "pass" for t in tests)
    print("check_verify: OK: {} tests ({} passed, {} not applicable), {} models, {} PNGs, {:.1f} s".format(
        len(tests), n_pass, len(tests) - n_pass, len(models), len(images), secs))


if __name__ == "__main__":
    main()
