#!/usr/bin/env python3
"""The record of a deck's grid study that a run reads (penetration.convergence_record).

From one or more studies of validation/perforation_convergence.py (each DIR with convergence.json
and the levels' folders h_<h>mm/), takes the quantities named, each from its study: per level its
value and, from the three finest, the observed order and the Richardson estimate the study
computed. Every level must share one physics fingerprint (the hash of its resolved.yaml without
what a study varies, src/deck/physics_fingerprint.hpp, computed here the same way); the record
keeps it, and a run whose fingerprint differs is told the record is not of its physics.

  /usr/bin/python3 validation/convergence_record.py --out examples/jet_casing_sandstone_mpm.convergence.json \\
      --study "docs/validation.md, The perforation demo under refinement" \\
      --quantity cavity_depth final_cavity_depth "tunnel depth" out/perfconv \\
      --quantity casing_mean_hole holes.casing.mean_diameter "casing hole" out/hole45

A quantity's study may stop its levels early (simulation.end_time is not part of the physics):
the casing's hole is set 45 us after firing, long before the jet is spent.

A configuration that is no level (patches of fine cells, a step per region) may be checked against
the study's converged estimates: `--checked NAME LABEL RUN_DIR QUANTITY[,QUANTITY]` records the
run's value of each quantity named (from its summary.json, at the quantity's summary key) and the
configuration fingerprint of its resolved.yaml (the physics fingerprint with the grid kept). A run
of that very configuration then says how far from converged it is. With `--into RECORD` instead
of studies, the checked configurations are added to an existing record (its levels unchanged; a
record written anew with --out keeps none of an earlier one's). A run counts as a checked
configuration only while it reproduces the recorded values (src/analysis/convergence_statement.hpp):

  /usr/bin/python3 validation/convergence_record.py --into examples/jet_casing_sandstone_mpm.convergence.json \\
      --checked hole_patches "casing patches" out/demo-converged/hole casing_mean_hole
"""
import argparse
import json
import os
import sys

SKIPPED_SECTIONS = {"grid", "output"}
SKIPPED_KEYS = {"simulation": {"end_time", "threads"},
                "penetration": {"axis_radius", "stop_tolerance", "convergence_record"}}


def physics_fingerprint(resolved_yaml, with_grid=False):
    """FNV-1a (64 bits) of the resolved deck's lines but those physics_fingerprint.hpp leaves out;
    `with_grid` keeps the grid section (configuration_fingerprint)."""
    skipped_sections = SKIPPED_SECTIONS - ({"grid"} if with_grid else set())
    h = 14695981039346656037
    section = ""
    for line in resolved_yaml.split("\n"):
        if line and line[0] not in " #":
            section = line.split(":", 1)[0].strip()
        t = line.strip(" \t\r")
        if not t or t[0] == "#" or section in skipped_sections:
            continue
        key, _, value = t.partition(":")
        value = value.strip(" \t\r")
        second_level = line.startswith("  ") and not line.startswith("   ")
        if second_level and key in SKIPPED_KEYS.get(section, set()):
            continue
        if value in ("none", "~"):
            continue
        for c in (line + "\n").encode():
            h ^= c
            h = (h * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def configuration_fingerprint(resolved_yaml):
    """The physics and the cells (src/deck/physics_fingerprint.hpp, configuration_fingerprint)."""
    return physics_fingerprint(resolved_yaml, with_grid=True)


def level_dir(study, h):
    """The level's run folder, as perforation_convergence.py names it."""
    d = os.path.join(study, f"h_{h * 1e3:g}mm")
    if not os.path.isfile(os.path.join(d, "resolved.yaml")):
        sys.exit(f"{study}: no resolved.yaml of the level h = {h} m in {d}")
    return d


def quantity(name, summary_key, label, study):
    conv = json.load(open(os.path.join(study, "convergence.json")))
    est = conv["estimates"].get(name)
    if est is None:
        sys.exit(f"{study}: no estimate of '{name}'")
    # No Richardson estimate (differences that grow, or levels that oscillate): the quantity is
    # recorded as not converged, so that a run does not call its level converged on the others.
    levels, prints = [], set()
    for lv in conv["levels"]:
        if lv.get(name) is None:
            sys.exit(f"{study}: level h = {lv['h']} has no '{name}'")
        levels.append([lv["h"], lv[name] * 1e-3])  # the study's lengths are in mm
        prints.add(physics_fingerprint(open(os.path.join(level_dir(study, lv["h"]), "resolved.yaml")).read()))
    return {"label": label, "summary_key": summary_key, "unit": "m",
            "richardson": est["richardson"] * 1e-3 if est.get("richardson") is not None else None,
            "order": est.get("observed_order"),
            "levels": sorted(levels, reverse=True)}, prints


def at_dotted(obj, key):
    """The number at a dotted key of a summary's penetration object, or None."""
    for part in key.split("."):
        if not isinstance(obj, dict) or part not in obj:
            return None
        obj = obj[part]
    return obj if isinstance(obj, (int, float)) and not isinstance(obj, bool) else None


def checked(name, label, run_dir, names, quantities):
    """A configuration's values of the named quantities, from its run folder."""
    summary = json.load(open(os.path.join(run_dir, "summary.json")))
    if summary.get("status") != "completed":
        sys.exit(f"{run_dir}: the run did not complete (status {summary.get('status')}): its values are no answer")
    p = summary.get("penetration") or {}
    values = {}
    for q in names.split(","):
        if q not in quantities:
            sys.exit(f"--checked {name}: '{q}' is not a quantity of the record ({', '.join(quantities)})")
        v = at_dotted(p, quantities[q]["summary_key"])
        if v is None:
            sys.exit(f"{run_dir}: summary.json has no penetration.{quantities[q]['summary_key']}")
        values[q] = v
    fp = configuration_fingerprint(open(os.path.join(run_dir, "resolved.yaml")).read())
    if p.get("configuration_fingerprint") not in (None, fp):
        sys.exit(f"{run_dir}: the run wrote configuration fingerprint {p['configuration_fingerprint']}, "
                 f"this script computes {fp}")
    return {"label": label, "configuration_fingerprint": fp, "values": values}


def dumps(record):
    """The record as JSON, one line per level, so that a change of a value shows in a diff."""
    text = json.dumps(record, indent=1)
    for q in record["quantities"].values():
        for lv in q["levels"]:
            text = text.replace(json.dumps(lv, indent=1).replace("\n", "\n    "), json.dumps(lv), 1)
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", help="the record to write from the studies")
    ap.add_argument("--into", help="an existing record to add the --checked configurations to")
    ap.add_argument("--study", default="", help="where the study is documented")
    ap.add_argument("--quantity", nargs=4, action="append", default=[],
                    metavar=("NAME", "SUMMARY_KEY", "LABEL", "STUDY_DIR"),
                    help="a quantity of perforation_convergence.py, where a run's summary penetration object "
                         "holds it, its label, and the study that measured it")
    ap.add_argument("--checked", nargs=4, action="append", default=[],
                    metavar=("NAME", "LABEL", "RUN_DIR", "QUANTITIES"),
                    help="a configuration that is no level, checked against the estimates: its run folder and "
                         "the quantities (comma-separated names) it measured")
    a = ap.parse_args()
    if bool(a.out) == bool(a.into):
        sys.exit("give either --out with the studies (--quantity) or --into an existing record")
    if a.into:
        if a.quantity or not a.checked:
            sys.exit("--into adds --checked configurations to a record; its quantities stay as they are")
        record = json.load(open(a.into))
        record.setdefault("checked", {})
    else:
        if not a.quantity:
            sys.exit("--out needs at least one --quantity")
        record = {"study": a.study, "quantities": {}}
        prints = set()
        for name, key, label, study in a.quantity:
            record["quantities"][name], p = quantity(name, key, label, study)
            prints |= p
        if len(prints) != 1:
            sys.exit(f"the levels are not of one physics (fingerprints {sorted(prints)}): one record needs one deck")
        record["physics_fingerprint"] = prints.pop()
        if a.checked:
            record["checked"] = {}
    for name, label, run_dir, names in a.checked:
        record["checked"][name] = checked(name, label, run_dir, names, record["quantities"])
    prints = {}
    for name, c in record.get("checked", {}).items():
        other = prints.setdefault(c["configuration_fingerprint"], name)
        if other != name:
            sys.exit(f"checked configurations '{other}' and '{name}' are one configuration (fingerprint "
                     f"{c['configuration_fingerprint']}): one run is one configuration")
    path = a.out or a.into
    with open(path, "w") as f:
        f.write(dumps(record) + "\n")
    print(f"wrote {path} (fingerprint {record['physics_fingerprint']})")


if __name__ == "__main__":
    main()
