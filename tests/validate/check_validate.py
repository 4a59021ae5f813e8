#!/usr/bin/python3
"""`ballista validate` end to end.

1. The quick level of data/validation_catalogue.yaml: exit 0, validate.json lists every problem the
   catalogue runs at that level with every check passed, and report.html names each problem, its
   reference and bounds, and embeds a figure for each run problem.
2. The tool must be able to fail: the Gurney sandwich with a bound below its plate velocity exits 1
   and reports the check as failed; a deck that does not exist is a failed run with its log's end;
   the same bound marked as a known gap is reported as one and exits 0.
"""
import argparse
import html
import json
import os
import shutil
import subprocess
import sys

import yaml


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ballista", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    catalogue = os.path.join(a.source, "data", "validation_catalogue.yaml")

    out = os.path.join(a.out, "quick")
    rc = subprocess.run([a.ballista, "validate", "--level", "quick", "-o", out, "--threads", "1"]).returncode
    if rc != 0:
        fail(f"validate --level quick exited {rc}")
    with open(catalogue, encoding="utf-8") as f:
        problems = [p for p in yaml.safe_load(f)["problems"] if "quick" in p["levels"]]
    with open(os.path.join(out, "validate.json"), encoding="utf-8") as f:
        result = json.load(f)
    got = {p["id"]: p for p in result["problems"]}
    with open(os.path.join(out, "report.html"), encoding="utf-8") as f:
        report = f.read()
    for p in problems:
        r = got.get(p["id"])
        if r is None:
            fail(f"{p['id']} is not in validate.json")
        if r["status"] != "pass":
            fail(f"{p['id']}: {r['status']} ({r['checks']})")
        if len(r["checks"]) != len(p["checks"]) or any(c["value"] is None for c in r["checks"]):
            fail(f"{p['id']}: a check has no value: {r['checks']}")
        for text in (p["title"], p.get("reference", "")):
            if text and html.escape(text) not in report:
                fail(f"report.html does not show '{text}'")
        if p["kind"] == "run" and f"alt='{p['id']}' src='data:image/png;base64," not in report:
            fail(f"report.html has no figure for {p['id']}")
    if "ballista 0." not in result["info"]["version"]:
        fail(f"the report does not name the build: {result['info']['version']}")

    # A bound that cannot hold, and a run that cannot start.
    with open(catalogue, encoding="utf-8") as f:
        doc = yaml.safe_load(f)
    sandwich = next(p for p in doc["problems"] if p["id"] == "gurney_sandwich")
    sandwich["checks"][0]["max"] = 100.0
    broken = dict(sandwich, id="missing_deck", deck="examples/no_such_deck.yaml")
    bad = os.path.join(a.out, "bad_catalogue.yaml")
    with open(bad, "w", encoding="utf-8") as f:
        yaml.safe_dump({"problems": [sandwich, broken]}, f)
    out = os.path.join(a.out, "bad")
    tool = os.path.join(a.source, "tools", "validate.py")
    rc = subprocess.run([sys.executable, tool, "--ballista", a.ballista, "--catalogue", bad, "--root", a.source,
                         "-o", out, "--level", "quick", "--threads", "1"]).returncode
    if rc != 1:
        fail(f"a bound below the value must exit 1, got {rc}")
    with open(os.path.join(out, "validate.json"), encoding="utf-8") as f:
        got = {p["id"]: p for p in json.load(f)["problems"]}
    if got["gurney_sandwich"]["status"] != "fail" or got["gurney_sandwich"]["checks"][0]["status"] != "fail":
        fail(f"the impossible bound passed: {got['gurney_sandwich']}")
    if got["missing_deck"]["status"] != "fail" or "exit status" not in got["missing_deck"]["message"]:
        fail(f"the missing deck did not fail as a run: {got['missing_deck']}")
    # The same impossible bound as a documented known gap: reported, and the report does not fail.
    gap = dict(sandwich, id="gap", known_gap="a documented difference")
    with open(bad, "w", encoding="utf-8") as f:
        yaml.safe_dump({"problems": [gap]}, f)
    out = os.path.join(a.out, "gap")
    rc = subprocess.run([sys.executable, tool, "--ballista", a.ballista, "--catalogue", bad, "--root", a.source,
                         "-o", out, "--level", "quick", "--threads", "1"]).returncode
    with open(os.path.join(out, "validate.json"), encoding="utf-8") as f:
        status = json.load(f)["problems"][0]["status"]
    if rc != 0 or status != "known gap":
        fail(f"a known gap must be reported as such with exit 0: exit {rc}, status {status}")
    print("validate: quick level passed; an impossible bound and a missing deck fail, a known gap is reported")


if __name__ == "__main__":
    main()
