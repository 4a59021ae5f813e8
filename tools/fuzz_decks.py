#!/usr/bin/env python3
"""Fuzz the ballista command line with mutated input (issue 11, "Hardening"; issue 35, its second round).

Sources (each case mutates one of them):
  run:<stem>      examples/*.yaml (not drive_*) and validation/rod_sandstone_reduced.yaml through
                  `ballista run DECK -o OUT --no-plots -q --threads 1`, made small and short first
                  by --set overrides (coarse grid.cell_size, short end_time, simulation.max_steps);
  drive:<stem>    examples/drive_*.yaml through `ballista drive DECK -o OUT -q`;
  ftable:<stem>   an F-table CSV (examples/*.csv) mutated, driven by a drive deck that names it;
  jettable        the jet segment table of examples/jet_casing_sandstone_mpm.yaml written as a CSV
                  (jet.file) and mutated;
  models:<name>   `ballista models NAME -p key=value ...` with mutated parameters and options;
and, since issue 35 (about 15 % of the cases; --kinds picks kinds):
  solver:<stem>   targeted mutations of the peridynamics, OTM and detonation decks (pd_*,
                  exploding_cylinder_pd, taylor_bar_otm*, explosive_sandwich_mpm): the solver's own
                  section keys, detonation points, times, edge_radius and burn_cells,
                  bodies[].point_spacing, grid.boundary faces, an explosive material no body uses
                  (tools/fuzz_solvers.py);
  overlap:<stem>  two bodies that overlap by several lattice cells, or that exactly touch (a shared
                  face), in the multi-body decks and by a copy or a split of a body in the others
                  (tools/fuzz_solvers.py);
  checkpoint:<stem> a short run with checkpoints, restarted with a later end time from an undamaged
                  copy (the reference) and from a damaged one: bit flips, truncation, swapped names,
                  a checkpoint of another run, an empty file, all deleted (tools/fuzz_checkpoints.py);
  concurrent:<stem> two runs into one folder at once (tools/fuzz_folders.py);
  userfile:<stem> a run into a folder holding user files (tools/fuzz_folders.py).

Mutations: deleted keys, wrong types, non-finite and extreme values, unknown and duplicate keys,
truncation at a random byte, binary garbage, YAML alias bombs, multiple documents, custom tags,
very long strings, deep nesting, and (for tables) bad rows and cells.

Every case runs in its own process group with a time limit (then the group is killed), an
address-space limit and an output-size limit. Outcomes:
  ok                 exit 0 and every number printed or written (stdout `name = value` lines,
                     summary.json, *.csv, the models' --json) finite;
  rejected           exit 1/2/3 (or another small status) with a message;
  failures:          signal (killed by a signal), uncaught ('terminate called', sanitizer or assertion
                     text), hang (time limit), nonfinite_success (exit 0 with nan/inf/null numbers),
                     error_too_long (stderr over --max-error-chars, 4000), silent_failure (non-zero
                     exit without any message), runaway_output (output folder over --max-output-mb),
                     out_of_memory (std::bad_alloc under --mem-limit-mb: an unbounded allocation or a
                     size check that ignores the process's limit), ignored_input (exit 0 although the
                     input had a duplicate or unknown key, a custom tag, a second document or a table
                     row the summary does not count), baseline_failed (see --baseline);
                     overlap_accepted (exit 0, or a refusal that does not name both bodies, on a deck
                     built with two clearly overlapping bodies), touching_refused (touching bodies
                     refused with a message about an overlap), corrupt_checkpoint_accepted (a restart
                     from a damaged checkpoint folder exits 0 with results other than the undamaged
                     folder's), concurrent_runs_mixed (two runs into one folder at once: both exit 0,
                     neither completes, or the surviving folder is inconsistent), user_file_deleted
                     (a user's file in the results folder deleted or changed by a run).
The output folder gets results.jsonl (one line per case), summary.json and summary.md, and for
every failing case cases/<id>/ with the mutated input files, repro.sh (the exact command line) and
the captured stdout/stderr. Case k depends only on (--seed, k): `--only k` reruns one case.
Exit status 1 if any failure class occurred, else 0.

  /usr/bin/python3 tools/fuzz_decks.py --ballista build/ballista --out out/fuzz --seed 1 --cases 200 --jobs 2
  /usr/bin/python3 tools/fuzz_decks.py --ballista build/ballista --out out/fuzz35 --seed 1 --cases 10000 \
      --jobs 2 --kinds new      # only the issue-35 kinds (solver, overlap, checkpoint, concurrent, userfile)
"""
import argparse
import concurrent.futures
import json
import math
import os
import random
import re
import resource
import shlex
import shutil
import signal
import subprocess
import sys
import threading
import time
import types

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fuzz_yaml import (YamlSubsetError, _copy, _delete, _dotted, _flow, _is_number,  # noqa: E402
                       _paths, _set, yaml_dump, yaml_load)
import fuzz_checkpoints  # noqa: E402
import fuzz_folders  # noqa: E402
import fuzz_solvers  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

FAILURE_CLASSES = ["signal", "uncaught", "hang", "nonfinite_success", "error_too_long", "silent_failure",
                   "runaway_output", "out_of_memory", "ignored_input", "baseline_failed",
                   # issue 35
                   "overlap_accepted", "touching_refused", "corrupt_checkpoint_accepted", "concurrent_runs_mixed",
                   "user_file_deleted"]
CORE_TAGS = ("!!str", "!!int", "!!float", "!!map", "!!seq", "!!bool", "!!null")
ALL_CLASSES = ["ok", "rejected"] + FAILURE_CLASSES

# --set overrides that make each run deck small and short (coarse grid as in tests/examples, a short
# end time); simulation.max_steps is added to every run case (MAX_STEPS) unless it is the mutated key.
RUN_REDUCTIONS = {
    "axis_aligned_mms": {"grid.cell_size": "0.25", "simulation.end_time": "0.002"},
    "elastic_disks": {"grid.cell_size": "0.05", "simulation.end_time": "0.3"},
    "taylor_bar_mpm": {"grid.cell_size": "0.8e-3", "simulation.end_time": "5.0e-6"},
    "taylor_bar_mpm_3d": {"grid.cell_size": "1.6e-3", "simulation.end_time": "5.0e-6"},
    "taylor_bar_jc_mpm": {"grid.cell_size": "0.8e-3", "simulation.end_time": "5.0e-6"},
    "thick_cylinder": {"grid.cell_size": "0.1", "simulation.end_time": "6.0e-4"},
    "sandstone_rod_impact_mpm": {"grid.cell_size": "1.0e-3", "simulation.end_time": "2.0e-6"},
    "jet_casing_sandstone_mpm": {"grid.cell_size": "2.0e-3", "grid.refine": "[]", "grid.patches": "[]",
                                 "mpm.multirate": "none", "simulation.end_time": "5.0e-6"},
    "rod_sandstone_mpm": {"grid.cell_size": "2.0e-3", "simulation.end_time": "5.0e-6"},
    "rod_billet_4130_mpm": {"grid.cell_size": "1.0e-3", "simulation.end_time": "5.0e-6"},
    "rod_sandstone_reduced": {"grid.cell_size": "2.0e-3", "simulation.end_time": "5.0e-6"},
    # 126k points at the deck's 0.86 mm: the bond families alone took over 20 s under the sanitizers.
    "exploding_cylinder_pd": {"grid.cell_size": "1.72e-3", "simulation.end_time": "1.0e-6"},
    # The 3D peridynamic decks at their tests/examples sizes: at the decks' own the bond families
    # alone took 3 to 9 s a case.
    "pd_lps_kalthoff_winkler": {"grid.cell_size": "0.002", "simulation.end_time": "1.0e-6"},
    "munition_case_pd": {"grid.cell_size": "1.72e-3", "bodies.1.point_spacing": "3.44e-3",
                         "simulation.end_time": "1.0e-6"},
    "pd_disk_indent": {"bodies.0.shape.radius": "0.0050001", "simulation.end_time": "1.0e-6"},
    # The charge and the well in one run: 85k points and a program burn at the deck's cells.
    "shaped_charge_perforation": {"grid.cell_size": "1.0e-3", "grid.refine": "[]", "simulation.end_time": "1.0e-6"},
    "perforating_gun_shot": {"grid.cell_size": "1.0e-3", "grid.refine": "[]", "simulation.end_time": "1.0e-6"},
}
DEFAULT_RUN_REDUCTION = {"simulation.end_time": "1.0e-6"}
MAX_STEPS = 30
# Drive decks: fewer steps (tests/examples sizes or smaller).
DRIVE_REDUCTIONS = {
    "drive_a1_frame_indifference": {"drive.substeps": "200", "drive.record_every": "50"},
    "drive_uniaxial_stress_j2": {"drive.legs.0.steps": "100"},
    "drive_sandstone_triaxial": {"drive.legs.0.steps": "20", "drive.legs.1.steps": "100"},
}
# Keys that set the amount of work: huge (valid) integers there would only make a long run.
WORK_KEYS = {"steps", "substeps", "max_steps", "particles_per_cell", "history_every", "record_every"}

# `ballista models`: a valid parameter set for each model (SI units).
MODELS = {
    "birkhoff": {"L": "0.07354", "rho_p": "19235", "rho_t": "2300", "V": "3300"},
    "particulated-jet": {"L": "0.07354", "lambda": "1.5", "rho_avg": "8000", "rho_t": "2300", "V": "6000"},
    "pack-evans": {"L": "0.07354", "lambda": "1", "rho_p": "19235", "rho_t": "2300", "alpha": "1",
                   "sigma_y": "50e6", "V": "3300", "r": "0.005", "penalty_outside_root": "0"},
    "eichelberger": {"L": "0.07354", "lambda": "1", "rho_p": "19235", "rho_t": "2300", "R": "1e9", "Y": "5e8",
                     "V": "3300"},
    "tate": {"L": "0.1", "rho_p": "17600", "rho_t": "7850", "R": "5e9", "Y": "1.5e9", "V": "2000",
             "steps_per_transit": "200"},
    "gladkikh": {"L": "0.07354", "rho_p": "8900", "rho_t": "2300", "V_tip": "9000", "V_tail": "1500"},
    "grove": {"L": "0.07354", "rho_d": "7000", "rho_s": "8900", "rho_t": "2300", "R": "1e9", "Y": "5e8",
              "V": "5000"},
    "harvey": {"P_ref": "0.3", "alpha0": "1e-8", "sigma_ucs": "50e6", "P_c": "30e6", "P_p": "10e6",
               "porosity": "0.2"},
    "orphal-anderson": {"a": "-500", "b": "0.9", "rho_p": "17600", "rho_t": "7850", "V": "2000"},
    "orphal-anderson-fit": {"rho_p": "17600", "rho_t": "7850"},
    "pack-evans-fit": {"P": "0.2", "r": "0.005", "L": "0.07354", "rho_p": "19235", "rho_t": "2300", "lambda": "1",
                       "sigma_y": "50e6", "V": "3300", "penalty_outside_root": "1"},
}
FIT_SERIES = {"orphal-anderson-fit": (["1000", "2000", "3000"], ["400", "1000", "1600"])}

EXTREME_NUMBERS = ["nan", "NaN", ".nan", "-nan", "inf", "-inf", ".inf", "-.inf", "+.inf", "Infinity", "1e308",
                   "-1e308", "1.7976931348623157e308", "1e309", "-1e400", "0", "-0", "0.0", "-0.0", "1e-300",
                   "-1e-300", "4.9e-324", "1e-320", "-1", "-1e-9", "9223372036854775807", "9223372036854775808",
                   "-9223372036854775809", "18446744073709551616", "4294967296", "2147483648",
                   "1" + "0" * 400, "0x7fffffff", "1e+", "1.2.3", "1,5", "0.1e-3e2",
                   # large but finite, for quantities with a physical range (strains, positions, ...)
                   "-800", "800", "1e6", "-1e6", "1e30", "-1e30", "1e-30", "1e100", "1e-12", "0.5", "2"]
WRONG_TYPES = ["abc", "\"42\"", "'nan'", "{a: 1}", "{}", "[]", "[1, 2]", "[[1, 2], [3]]", "~", "null", "true", "no",
               "\"\"", "2026-11-24", "[nan, inf]", "{x: {y: {z: 1}}}", "!!binary aGVsbG8=", "1.5", "-7", "0"]
TAGS = ["!!python/object/apply:os.system [\"true\"]", "!custom", "!!str", "!!int", "!!float", "!!map", "!!seq",
        "!<tag:example.com,2000:x>", "!!binary", "!!timestamp", "!local"]


# ---------------------------------------------------------------------------------------------
# Mutations
# ---------------------------------------------------------------------------------------------
def long_string(rng):
    n = rng.choice([3000, 70000, 200000])
    kind = rng.randrange(4)
    if kind == 0:
        return "x" * n
    if kind == 1:
        return "1" * n
    if kind == 2:
        return "0." + "0" * n + "1"
    return "\"" + "\\u00e9" * (n // 6) + "\""


def alias_bomb(rng, levels=None):
    levels = levels or rng.choice([6, 9])
    lines = ['fuzz_lol0: &a0 ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]']
    for i in range(1, levels):
        lines.append(f"fuzz_lol{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]")
    return lines, f"*a{levels - 1}"


def deep_nesting(rng):
    n = rng.choice([200, 5000, 100000])
    return rng.choice(["[" * n + "]" * n, "{a: " * n + "1" + "}" * n, "[" * n])


def tree_mutation(rng, tree, kind, protect=()):
    """Mutate the parsed deck in place; returns (description, dotted path or None)."""
    paths = [(p, v) for p, v in _paths(tree) if _dotted(p) not in protect]
    if not paths:
        return "nothing to mutate", None
    if kind == "delete_key":
        p, _ = rng.choice(paths)
        _delete(tree, p)
        return f"delete {_dotted(p)}", _dotted(p)
    if kind == "wrong_type":
        p, v = rng.choice(paths)
        new = rng.choice(WRONG_TYPES)
        _set(tree, p, new)
        return f"{_dotted(p)} = {new}", _dotted(p)
    if kind == "extreme_value":
        leaves = [(p, v) for p, v in paths if _is_number(v)] or paths
        p, v = rng.choice(leaves)
        new = rng.choice(EXTREME_NUMBERS)
        if p[-1] in WORK_KEYS and _is_number(new) and not _is_float_text(new):
            try:
                if int(new) > 10**7:
                    new = "1e30"
            except ValueError:
                pass
        _set(tree, p, new)
        return f"{_dotted(p)} = {new}", _dotted(p)
    if kind == "unknown_key":
        maps = [(p, v) for p, v in paths if isinstance(v, dict)] + [((), tree)]
        p, v = rng.choice(maps)
        if v and rng.random() < 0.5:
            k = rng.choice(list(v.keys()))
            k2 = k[:-1] + chr(ord(k[-1]) ^ 1) if k else "x"
            if k2.isdigit():  # 22 -> 23 is another valid component of a drive leg, not a typo
                k2 = k + "x"
        else:
            k2 = rng.choice(["fuzz_unknown", "x", "Density", "1", "\"\"", "?", "-", "cell size", "<<"])
        v[k2] = rng.choice(["1", "abc", "{a: 1}", "[1]", "~"])
        if p == ("materials",):  # a new material name: not an unknown key as such
            return f"new entry {_dotted(p + (k2,))}", _dotted(p + (k2,))
        return f"unknown key {_dotted(p + (k2,))} (must be rejected)", _dotted(p + (k2,))
    if kind == "list_shape":
        lists = [(p, v) for p, v in paths if isinstance(v, list)]
        if not lists:
            return tree_mutation(rng, tree, "wrong_type", protect)
        p, v = rng.choice(lists)
        op = rng.randrange(5)
        if op == 0 or not v:
            v.clear()
            return f"{_dotted(p)} = []", _dotted(p)
        if op == 1:
            v.pop(rng.randrange(len(v)))
            return f"{_dotted(p)} drop an item", _dotted(p)
        if op == 2:
            v.extend(_copy(v[-1]) for _ in range(rng.choice([1, 3])))
            return f"{_dotted(p)} repeat the last item", _dotted(p)
        if op == 3:
            v.append(rng.choice(EXTREME_NUMBERS))
            return f"{_dotted(p)} extra item", _dotted(p)
        v.reverse()
        return f"{_dotted(p)} reversed", _dotted(p)
    if kind == "swap_values":
        a, va = rng.choice(paths)
        b, vb = rng.choice(paths)
        try:
            _set(tree, a, _copy(vb))
        except (KeyError, IndexError, TypeError):
            return "swap failed", None
        return f"{_dotted(a)} = value of {_dotted(b)}", _dotted(a)
    if kind == "scale_number":
        # a plausible but unusual value: the deck stays valid more often and reaches the solver
        leaves = [(p, v) for p, v in paths if _is_number(v)]
        if not leaves:
            return tree_mutation(rng, tree, "extreme_value", protect)
        p, v = rng.choice(leaves)
        f = rng.choice([-1, 0, 1e-6, 1e-3, 0.1, 0.5, 0.99, 1.01, 2, 10, 1e3, 1e6])
        if p[-1] in ("cell_size", "particles_per_cell") and 0 < f < 1:
            f = 1 / f  # a finer resolution is only a longer (valid) run; coarser and degenerate values are kept
        x = float(v) * f
        if p[-1] in WORK_KEYS:
            x = min(abs(x), 1e4)
        new = repr(int(x)) if re.fullmatch(r"[-+]?\d+", v) and abs(x) < 1e15 else repr(x)
        _set(tree, p, new)
        return f"{_dotted(p)} = {new} ({v} x {f:g})", _dotted(p)
    if kind == "long_string":
        p, v = rng.choice(paths)
        _set(tree, p, long_string(rng))
        return f"{_dotted(p)} = long string", _dotted(p)
    if kind == "deep_nesting":
        p, v = rng.choice(paths)
        _set(tree, p, deep_nesting(rng))
        return f"{_dotted(p)} = deep nesting", _dotted(p)
    if kind == "custom_tag":
        leaves = [(p, v) for p, v in paths if not isinstance(v, (dict, list))] or paths
        p, v = rng.choice(leaves)
        tag = rng.choice(TAGS)
        _set(tree, p, tag + " " + _flow(v))
        if not tag.startswith(CORE_TAGS):
            return f"{_dotted(p)} tagged {tag} (custom tag: must be rejected)", _dotted(p)
        return f"{_dotted(p)} tagged {tag}", _dotted(p)
    raise ValueError(kind)


def _is_float_text(s):
    return any(c in s.lower() for c in ".en") or "inf" in s.lower()


TREE_KINDS = ["delete_key", "wrong_type", "extreme_value", "extreme_value", "extreme_value", "unknown_key",
              "list_shape", "swap_values", "long_string", "deep_nesting", "custom_tag", "scale_number",
              "scale_number", "scale_number", "scale_number"]
TEXT_KINDS = ["truncate", "garbage", "alias_bomb", "multi_document", "duplicate_key", "tag_document", "bad_indent",
              "empty", "nul_bytes", "bad_utf8", "crlf_tabs", "recursive_alias", "parser_killer"]
# Inputs that made YAML parsers loop, exhaust memory or crash (yaml-cpp issues #2, #499, #793, #938,
# #1040; "," alone loops in yaml-cpp 0.7 LoadAll).
PARSER_KILLERS = [",", ",\n", "[:", "{:", "[[:", "{!\xdb:", "{# ke\ny{:", "- !+(.,.)", "bad YAML: [", "? ,", "[", "{",
                  "&a [*a]", "*a", "!<!> x", "- - - - - - - -", "a: &a\n  b: *a\n", ": :", "--- |\n  x\n ---",
                  "\"\\u", "'", "%YAML 9.9\n---\na: 1"]


def text_mutation(rng, text, kind):
    b = text.encode()
    if kind == "truncate":
        n = rng.randrange(len(b) + 1)
        return b[:n], f"truncated at byte {n}"
    if kind == "garbage":
        op = rng.randrange(3)
        junk = bytes(rng.randrange(256) for _ in range(rng.choice([1, 8, 64, 4096])))
        if op == 0:
            return junk, "replaced by binary garbage"
        i = rng.randrange(len(b) + 1)
        if op == 1:
            return b[:i] + junk + b[i:], f"binary garbage inserted at byte {i}"
        return b[:i] + junk + b[i + len(junk):], f"binary garbage over bytes {i}.."
    if kind == "alias_bomb":
        lines, alias = alias_bomb(rng)
        place = rng.randrange(3)
        if place == 0:  # as unknown top-level keys
            return ("\n".join(lines) + "\n" + text).encode(), "billion laughs at top level (must be rejected)"
        # use the alias as the value of a real key
        keylines = [i for i, l in enumerate(text.splitlines()) if re.match(r"^\s+[A-Za-z_]\w*:\s*\S", l)]
        tl = text.splitlines()
        if keylines:
            i = rng.choice(keylines)
            m = re.match(r"^(\s+[A-Za-z_]\w*:)", tl[i])
            tl[i] = m.group(1) + " " + alias
        if place == 1:
            return ("\n".join(lines) + "\n" + "\n".join(tl) + "\n").encode(), \
                "billion laughs used as a value (must be rejected)"
        # anchors inside a map that is a real key: keep them in a fuzz key
        return ("fuzz_bomb:\n" + "\n".join("  " + l for l in lines) + "\n" + "\n".join(tl) + "\n").encode(), \
            "billion laughs nested (must be rejected)"
    if kind == "multi_document":
        op = rng.randrange(4)
        if op == 0:
            return (text + "\n---\n" + text).encode(), "the deck twice as two documents (must be rejected)"
        if op == 1:
            return (text + "\n---\nsimulation: {end_time: 1}\n").encode(), "a second document (must be rejected)"
        if op == 2:
            return ("---\n" + text + "\n...\n").encode(), "explicit document markers, one document"
        return ("%YAML 1.2\n---\n" + text + "\n...\n%YAML 1.2\n---\n{a: 1}\n").encode(), \
            "directives, two documents (must be rejected)"
    if kind == "duplicate_key":
        tl = text.splitlines()
        keylines = [i for i, l in enumerate(tl) if re.match(r"^\s*[A-Za-z_]\w*:", l)]
        if not keylines:
            return b + b"\nx: 1\nx: 2\n", "duplicate top-level key"
        i = rng.choice(keylines)
        m = re.match(r"^(\s*[A-Za-z_]\w*:)(.*)$", tl[i])
        if m.group(2).strip():
            dup = m.group(1) + " " + rng.choice(EXTREME_NUMBERS + WRONG_TYPES)
            tl.insert(i + 1, dup)
        else:  # a block key: repeat the key with an empty map after the block
            j = i + 1
            ind = len(tl[i]) - len(tl[i].lstrip())
            while j < len(tl) and (len(tl[j]) - len(tl[j].lstrip()) > ind or not tl[j].strip()):
                j += 1
            tl.insert(j, m.group(1) + " " + rng.choice(["{}", "[]", "1", "~"]))
        return ("\n".join(tl) + "\n").encode(), f"duplicate key {m.group(1).strip()} (must be rejected)"
    if kind == "tag_document":
        tag = rng.choice(["!custom\n", "--- !!map\n", "--- !python/object:x\n", "%TAG ! tag:x.com,2000:\n---\n"])
        return (tag + text).encode(), "tagged document " + tag.strip().replace("\n", " ") + \
            (" (custom tag: must be rejected)" if "!custom" in tag or "python" in tag else "")
    if kind == "bad_indent":
        tl = text.splitlines()
        if tl:
            i = rng.randrange(len(tl))
            tl[i] = rng.choice([" ", "   ", "\t", "      "]) + tl[i]
        return ("\n".join(tl) + "\n").encode(), f"indentation changed at line {i + 1 if tl else 0}"
    if kind == "empty":
        return rng.choice([b"", b"\n", b"---\n", b"~\n", b"[]\n", b"42\n", b"{}\n", b"\"just a string\"\n"]), \
            "empty or scalar document"
    if kind == "nul_bytes":
        i = rng.randrange(len(b) + 1)
        return b[:i] + b"\x00" * rng.choice([1, 100]) + b[i:], f"NUL bytes at {i}"
    if kind == "bad_utf8":
        i = rng.randrange(len(b) + 1)
        return b[:i] + rng.choice([b"\xff\xfe", b"\xc3", b"\xed\xa0\x80", b"\xef\xbb\xbf"]) + b[i:], \
            f"invalid UTF-8 at {i}"
    if kind == "recursive_alias":
        # an anchor referenced inside its own definition: a recursive node
        tl = text.splitlines()
        keylines = [i for i, l in enumerate(tl) if re.match(r"^\s*[A-Za-z_]\w*:", l)]
        form = rng.randrange(3)
        if not keylines:
            return b"&r [*r]\n", "recursive alias document"
        i = rng.choice(keylines)
        m = re.match(r"^(\s*)([A-Za-z_]\w*:)", tl[i])
        if form == 0:
            tl[i] = m.group(1) + m.group(2) + " &r [1, *r]"
        elif form == 1:
            tl[i] = m.group(1) + m.group(2) + " &r {x: *r}"
        else:
            tl.insert(i + 1, m.group(1) + "  fuzz_self: *r")
            tl[i] = m.group(1) + m.group(2) + " &r"
        return ("\n".join(tl) + "\n").encode(), f"recursive alias at line {i + 1} (form {form})"
    if kind == "parser_killer":
        k = rng.choice(PARSER_KILLERS).encode("latin-1")
        op = rng.randrange(3)
        if op == 0:
            return k, f"known parser killer {k!r}"
        if op == 1:
            return k + b"\n" + b, f"known parser killer {k!r} prepended"
        return b + b"\n---\n" + k + b"\n", f"known parser killer {k!r} as a second document"
    if kind == "crlf_tabs":
        return text.replace("\n", "\r\n").replace("  ", "\t").encode(), "CRLF line ends and tabs"
    raise ValueError(kind)


# ---------------------------------------------------------------------------------------------
# Sources and cases
# ---------------------------------------------------------------------------------------------
def discover_sources():
    ex = os.path.join(REPO, "examples")
    sources = []
    for f in sorted(os.listdir(ex)):
        stem, ext = os.path.splitext(f)
        if ext == ".yaml":
            sources.append(("drive" if stem.startswith("drive_") else "run", stem, os.path.join(ex, f)))
        elif ext == ".csv":
            sources.append(("ftable", stem, os.path.join(ex, f)))
    val = os.path.join(REPO, "validation", "rod_sandstone_reduced.yaml")
    if os.path.exists(val):
        sources.append(("run", "rod_sandstone_reduced", val))
    jet = os.path.join(ex, "jet_casing_sandstone_mpm.yaml")
    if os.path.exists(jet):
        sources.append(("jettable", "jet_casing_sandstone_mpm", jet))
    for m in MODELS:
        sources.append(("models", m, None))
    # issue 35 (appended: the earlier sources keep their baseline numbers)
    for kind, decks in (("solver", fuzz_solvers.SOLVER_DECKS), ("overlap", fuzz_solvers.OVERLAP_DECKS),
                        ("checkpoint", fuzz_checkpoints.DECKS), ("concurrent", fuzz_folders.CONCURRENT_DECKS),
                        ("userfile", fuzz_folders.USERFILE_DECKS)):
        for stem in sorted(decks):
            if os.path.exists(os.path.join(ex, stem + ".yaml")):
                sources.append((kind, stem, os.path.join(ex, stem + ".yaml")))
    return sources


# Sampling weights per source kind (each kind's weight is split over its sources).
KIND_WEIGHTS = {"run": 0.45, "drive": 0.14, "ftable": 0.1, "jettable": 0.06, "models": 0.25}
# Issue 35's kinds, as shares of all cases (with every kind present: 15 % in all). Whether case k is
# one of them is drawn from its own stream ("seed:k:kind"), so the other cases are the same as
# before these kinds existed. Checkpoint and concurrent cases run 2-4 commands each.
NEW_KIND_WEIGHTS = {"solver": 0.06, "overlap": 0.035, "checkpoint": 0.025, "concurrent": 0.015, "userfile": 0.015}
OLD_SHARE = 0.85
MULTI_STEP = {"checkpoint", "concurrent", "userfile"}


def pick_source(rng, sources):
    kinds = [k for k in KIND_WEIGHTS if any(s[0] == k for s in sources)]
    kind = rng.choices(kinds, weights=[KIND_WEIGHTS[k] for k in kinds])[0]
    return rng.choice([s for s in sources if s[0] == kind])


def choose_source(index, seed, rng, sources):
    new_kinds = [k for k in NEW_KIND_WEIGHTS if any(s[0] == k for s in sources)]
    old_present = any(s[0] in KIND_WEIGHTS for s in sources)
    if new_kinds:
        wn = sum(NEW_KIND_WEIGHTS[k] for k in new_kinds)
        rk = random.Random(f"{seed}:{index}:kind")
        if rk.random() < wn / (wn + (OLD_SHARE if old_present else 0.0)):
            kind = rk.choices(new_kinds, weights=[NEW_KIND_WEIGHTS[k] for k in new_kinds])[0]
            return rk.choice([s for s in sources if s[0] == kind])
    return pick_source(rng, sources)


def read_text(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def mutate_deck(rng, text, protect=()):
    """A mutated deck: (bytes, [descriptions], [dotted paths targeted])."""
    descs, targets = [], []
    if rng.random() < 0.62:
        try:
            tree = yaml_load(text)
        except YamlSubsetError:
            tree = None
        if isinstance(tree, dict):
            for _ in range(rng.choice([1, 1, 1, 2, 3])):
                d, t = tree_mutation(rng, tree, rng.choice(TREE_KINDS), protect)
                descs.append(d)
                if t:
                    targets.append(t)
            # an input that must be rejected (unknown key, custom tag) may have been undone by a later
            # mutation of the same part of the deck: keep the claim only if it is still in the tree
            flat = {_dotted(p): v for p, v in _paths(tree)}
            for i, d in enumerate(descs):
                m = re.match(r"^(unknown key|(\S+) tagged) ", d)
                if "must be rejected" in d and m:
                    path = d.split()[2] if d.startswith("unknown key") else m.group(2)
                    v = flat.get(path)
                    if v is None or (not d.startswith("unknown key") and not str(v).startswith("!")):
                        descs[i] = d.replace("must be rejected", "undone later")
            out = yaml_dump(tree) + "\n"
            if rng.random() < 0.15:
                data, d = text_mutation(rng, out, rng.choice(TEXT_KINDS))
                descs = [x.replace("must be rejected", "then text-mutated") for x in descs]
                return data, descs + [d], targets
            return out.encode(), descs, targets
    data, d = text_mutation(rng, text, rng.choice(TEXT_KINDS))
    return data, [d], targets


def set_mutation(rng, reductions):
    """A mutated --set override aimed at a size key or any common key: (key, value, description)."""
    keys = list(reductions) + ["simulation.max_steps", "simulation.cfl", "simulation.end_time", "grid.cell_size",
                               "output.interval", "output.history_every", "simulation.damping",
                               "bodies.0.particles_per_cell", "grid.lower.0", "grid.upper.1", "materials",
                               "bodies.0.velocity.1", "simulation.dimension", "simulation", "bodies.7.name",
                               "nosuch.key", "", ".", "grid..cell_size", "bodies.-1.name"]
    k = rng.choice(keys)
    v = rng.choice(EXTREME_NUMBERS + WRONG_TYPES + ["1e-12", "1e-9", "1e12"])
    if k.rsplit(".", 1)[-1] in WORK_KEYS and _is_number(v) and not _is_float_text(v):
        try:
            if int(v) > 10**7:
                v = "1e30"
        except ValueError:
            pass
    return k, v


def csv_mutation(rng, text):
    lines = text.splitlines()
    data_idx = [i for i, l in enumerate(lines) if l.strip() and not l.lstrip().startswith("#")
                and re.match(r"^\s*[-+0-9.]", l)]
    op = rng.choice(["cell", "cell", "cell", "drop_cell", "add_cell", "drop_row", "dup_row", "swap_rows",
                     "header", "truncate", "garbage", "long_line", "empty", "many_rows", "blank_cells", "separator"])
    desc = op
    if op in ("cell", "drop_cell", "add_cell", "blank_cells") and data_idx:
        i = rng.choice(data_idx)
        cells = lines[i].split(",")
        j = rng.randrange(len(cells))
        if op == "cell":
            v = rng.choice(EXTREME_NUMBERS + ["abc", "", " ", "1e", "--1", "0x10", "1;2", "\"3\""])
            cells[j] = v
            desc = f"row {i + 1} cell {j} = {v[:40]}"
        elif op == "drop_cell":
            cells.pop(j)
            desc = f"row {i + 1} drop cell {j}"
        elif op == "add_cell":
            cells.insert(j, rng.choice(["0", "1", "nan"]))
            desc = f"row {i + 1} extra cell at {j}"
        else:
            cells = ["" for _ in cells]
            desc = f"row {i + 1} all cells empty"
        lines[i] = ",".join(cells)
    elif op == "drop_row" and data_idx:
        i = rng.choice(data_idx)
        lines.pop(i)
        desc = f"drop row {i + 1}"
    elif op == "dup_row" and data_idx:
        i = rng.choice(data_idx)
        lines.insert(i, lines[i])
        desc = f"duplicate row {i + 1} (repeated time)"
    elif op == "swap_rows" and len(data_idx) > 1:
        i, j = rng.sample(data_idx, 2)
        lines[i], lines[j] = lines[j], lines[i]
        desc = f"swap rows {i + 1} and {j + 1}"
    elif op == "header":
        hdr = [i for i, l in enumerate(lines) if l and not l.startswith("#") and not re.match(r"^\s*[-+0-9.]", l)]
        if hdr:
            lines[hdr[0]] = rng.choice(["", "t,F11", "a,b,c", lines[hdr[0]] + ",extra", "#" + lines[hdr[0]]])
        else:
            lines.insert(0, "t,x,y")
        desc = "header changed"
    elif op == "truncate":
        b = text.encode()
        n = rng.randrange(len(b) + 1)
        return b[:n], f"truncated at byte {n}"
    elif op == "garbage":
        data, d = text_mutation(rng, text, rng.choice(["garbage", "nul_bytes", "bad_utf8"]))
        return data, d
    elif op == "long_line":
        lines.append(",".join(["1"] * rng.choice([1000, 100000])))
        desc = "very long row"
    elif op == "empty":
        return rng.choice([b"", b"\n", b"#only a comment\n"]), "empty table"
    elif op == "many_rows" and data_idx:
        last = lines[data_idx[-1]].split(",")
        try:
            t0 = float(last[0])
        except ValueError:
            t0 = 1.0
        for k in range(rng.choice([2, 50])):
            last[0] = repr(t0 + (k + 1) * rng.choice([1e-300, 1.0, 1e300]))
            lines.append(",".join(last))
        desc = "appended rows with extreme time steps"
    elif op == "separator":
        return text.replace(",", rng.choice([";", " ", "\t", ",,"])).encode(), "other separator"
    return ("\n".join(lines) + "\n").encode(), desc


def table_rows(data):
    """Rows of a CSV table as a reader should count them: every line but blank ones, '#' comments
    and a first line that does not start with a number (the header). Lines end at '\n' (a '\r'
    inside a line, as binary garbage in a comment may have, does not start a new one)."""
    rows = [l.strip() for l in data.decode("utf-8", "replace").split("\n")]
    rows = [l for l in rows if l and not l.startswith("#")]
    if rows:
        try:
            float(re.split(r"[,;\s]+", rows[0])[0])
        except ValueError:
            rows = rows[1:]
    return len(rows)


def models_case(rng, name):
    """(argv after 'models', description)."""
    params = dict(MODELS[name])
    series = FIT_SERIES.get(name)
    extra, desc = [], []
    for _ in range(rng.choice([1, 1, 2]) if rng else 0):
        op = rng.choice(["extreme", "extreme", "extreme", "delete", "wrong", "unknown", "duplicate", "malformed",
                         "velocities", "rates", "long", "model_name", "json_path", "equal", "equal"])
        keys = list(params)
        if op == "equal" and len(keys) > 1:  # two parameters equal (R = Y, V_tip = V_tail, ...)
            k1, k2 = rng.sample(keys, 2)
            params[k2] = params[k1]
            if rng.random() < 0.5:
                params[k1] = params[k2] = rng.choice(EXTREME_NUMBERS[:24] + ["1e9", "1", "2300"])
            desc.append(f"{k2}={k1}={params[k1][:40]}")
        elif op == "extreme" and keys:
            k = rng.choice(keys)
            params[k] = rng.choice(EXTREME_NUMBERS)
            desc.append(f"{k}={params[k][:40]}")
        elif op == "delete" and keys:
            k = rng.choice(keys)
            del params[k]
            desc.append(f"no {k}")
        elif op == "wrong" and keys:
            k = rng.choice(keys)
            params[k] = rng.choice(["abc", "", "1,2", "[1]", "1 2", "0x10", "1e", "true", "--", "=1"])
            desc.append(f"{k}='{params[k]}'")
        elif op == "unknown":
            params[rng.choice(["bogus", "l", "RHO_P", "v", "", " ", "=", "rho p"])] = "1"
            desc.append("unknown parameter")
        elif op == "duplicate" and keys:
            k = rng.choice(keys)
            extra += ["-p", f"{k}={rng.choice(EXTREME_NUMBERS)}"]
            desc.append(f"duplicate {k}")
        elif op == "malformed":
            extra += ["-p", rng.choice(["L", "=", "L==1", "L=1=2", "", "L= 1", " L=1"])]
            desc.append("malformed -p")
        elif op == "velocities":
            vals = [rng.choice(EXTREME_NUMBERS + ["1000", "2000"]) for _ in range(rng.choice([1, 2, 5]))]
            extra += ["--velocities", ",".join(vals)]
            desc.append("--velocities " + ",".join(v[:20] for v in vals))
        elif op == "rates":
            vals = [rng.choice(EXTREME_NUMBERS + ["400", "1000"]) for _ in range(rng.choice([1, 2, 3, 4]))]
            extra += ["--rates", ",".join(vals)]
            desc.append("--rates " + ",".join(v[:20] for v in vals))
        elif op == "long" and keys:
            k = rng.choice(keys)
            params[k] = long_string(rng)[:100000]
            desc.append(f"{k}=long string")
        elif op == "model_name":
            name = rng.choice([name.upper(), name + " ", "", "list ", name[:-1], "x" * 5000])
            desc.append("model name changed")
        elif op == "json_path":
            extra += ["--json", rng.choice(["/nonexistent/dir/x.json", "/", "", "/dev/full"])]
            desc.append("bad --json path")
    argv = [name]
    for k, v in params.items():
        argv += ["-p", f"{k}={v}"]
    if series and not any(a in ("--velocities", "--rates") for a in extra):
        argv += ["--velocities", ",".join(series[0]), "--rates", ",".join(series[1])]
    return (argv + extra, desc) if rng else argv


def referenced_files(text, deck_path):
    """The files a source deck names by a path relative to its folder (`file: geometry/part.stl`,
    `convergence_record: study.json`), {relative path: bytes}, so that the case's copy of the deck
    finds them beside it."""
    out = {}
    for rel in re.findall(r"\b(?:file|convergence_record):\s*['\"]?([^\s,'\"}]+)", text):
        src = os.path.join(os.path.dirname(deck_path), rel)
        if not os.path.isabs(rel) and os.path.isfile(src):
            with open(src, "rb") as f:
                out[os.path.normpath(rel)] = f.read()
    return out


def make_case(index, seed, sources, case_dir, ballista, baseline=None):
    """Write the case's input files to case_dir; returns a dict with cmd, source, mutation.
    baseline: a source run without any mutation (--baseline: the reduced sizes must run ok)."""
    rng = random.Random(f"{seed}:{index}")
    kind, stem, path = baseline or choose_source(index, seed, rng, sources)
    mut = baseline is None
    os.makedirs(case_dir, exist_ok=True)
    out_dir = os.path.join(case_dir, "out")
    case = {"index": index, "source": f"{kind}:{stem}", "kind": kind}

    if kind == "run" or kind == "jettable":
        text = read_text(path)
        reductions = dict(RUN_REDUCTIONS.get(stem, DEFAULT_RUN_REDUCTION))
        reductions["simulation.max_steps"] = str(MAX_STEPS)
        files = {}
        if kind == "jettable":
            tree = yaml_load(text)
            jb = next(b for b in tree["bodies"] if isinstance(b, dict) and "jet" in b)
            rows = jb["jet"].pop("segments")
            jb["jet"]["file"] = "segments.csv"
            csv = "# radius,length,velocity,insert_time\n" + \
                "\n".join(",".join(r) for r in rows) + "\n"
            data, d = csv_mutation(rng, csv) if mut else (csv.encode(), "none")
            files["segments.csv"] = data
            case["expect_rows"] = ["penetration", "segments", table_rows(data)]
            deck = (yaml_dump(tree) + "\n").encode()
            descs, targets = ["segments.csv: " + d], []
        else:
            protect = ()
            data, descs, targets = mutate_deck(rng, text, protect) if mut else (text.encode(), [], [])
            deck = data
        sets = []
        if mut and kind == "run" and rng.random() < 0.12:
            k, v = set_mutation(rng, reductions)
            sets.append(f"{k}={v}")
            descs.append(f"--set {k}={v[:40]}")
            targets.append(k)
        if mut and kind == "run" and rng.random() < 0.04:
            # no max_steps cap: a vanishing time step or output interval must not run (or write) forever
            k = rng.choice(["simulation.cfl", "output.interval", "simulation.end_time"])
            v = rng.choice(["inf", "nan", "-1", "-0"] if k.endswith("end_time") else
                           ["1e-12", "1e-30", "1e-300", "4.9e-324", "0", "-0", "nan"])
            sets += [f"{k}={v}", "simulation.max_steps=0"]
            descs.append(f"--set {k}={v} --set simulation.max_steps=0 (uncapped)")
            targets += [k, "simulation.max_steps"]
        # A mutation of a reduction key replaces that reduction (the max_steps cap stays, unless it is
        # the mutated key itself: then the short end time bounds the run).
        for k, v in reductions.items():
            if not any(t == k or t.startswith(k + ".") or k.startswith(t + ".") for t in targets):
                sets.insert(0, f"{k}={v}")
        files["deck.yaml"] = deck
        files.update(referenced_files(text, path))
        for fn, data in files.items():
            os.makedirs(os.path.dirname(os.path.join(case_dir, fn)), exist_ok=True)
            with open(os.path.join(case_dir, fn), "wb") as f:
                f.write(data)
        cmd = [ballista, "run", os.path.join(case_dir, "deck.yaml"), "-o", out_dir, "--no-plots", "-q",
               "--threads", "1"]
        for s in sets:
            cmd += ["--set", s]
    elif kind in ("drive", "ftable"):
        files = {}
        sets = []
        if kind == "drive":
            text = read_text(path)
            red = dict(DRIVE_REDUCTIONS.get(stem, {}))
            # a table referenced by the deck is copied next to it
            for m in re.finditer(r"table:\s*([\w.\-]+\.csv)", text):
                src = os.path.join(os.path.dirname(path), m.group(1))
                if os.path.exists(src):
                    with open(src, "rb") as f:
                        files[m.group(1)] = f.read()
            data, descs, targets = mutate_deck(rng, text) if mut else (text.encode(), [], [])
            if mut and rng.random() < 0.1:
                k = rng.choice(list(red) + ["drive.scale", "drive.noise", "drive.legs.0.duration",
                                            "drive.legs.0.strain.11", "drive.stress_tolerance", "drive.table",
                                            "materials"])
                v = rng.choice(EXTREME_NUMBERS + WRONG_TYPES)
                if k.rsplit(".", 1)[-1] in WORK_KEYS and _is_number(v) and not _is_float_text(v):
                    v = "1e30" if abs(float(v)) > 1e7 else v
                sets.append(f"{k}={v}")
                descs.append(f"--set {k}={v[:40]}")
                targets.append(k)
            files["deck.yaml"] = data
        else:
            deck_src = os.path.join(REPO, "examples", stem + ".yaml")
            red = dict(DRIVE_REDUCTIONS.get(stem, {"drive.substeps": "10"}))
            deck_text = read_text(deck_src) if os.path.exists(deck_src) else \
                "materials:\n  m:\n    model: linear_elastic\n    density: 1\n    bulk_modulus: 1e4\n" \
                "    shear_modulus: 1e4\ndrive:\n  table: table.csv\n"
            deck_text = re.sub(r"table:\s*[\w.\-]+\.csv", "table: table.csv", deck_text)
            data, d = csv_mutation(rng, read_text(path)) if mut else (read_text(path).encode(), "none")
            files["table.csv"] = data
            case["expect_rows"] = ["program", "rows", table_rows(data)]
            files["deck.yaml"] = deck_text.encode()
            descs, targets = ["table.csv: " + d], []
        for k, v in red.items():
            if not any(t == k or t.startswith(k + ".") or k.startswith(t + ".") for t in targets):
                sets.insert(0, f"{k}={v}")
        for fn, data in files.items():
            with open(os.path.join(case_dir, fn), "wb") as f:
                f.write(data)
        cmd = [ballista, "drive", os.path.join(case_dir, "deck.yaml"), "-o", out_dir, "-q"]
        for s in sets:
            cmd += ["--set", s]
        if mut and rng.random() < 0.05:
            opt = rng.choice(["--scale", "--noise"])
            v = rng.choice(EXTREME_NUMBERS)
            cmd += [opt, v]
            descs.append(f"{opt} {v[:40]}")
            if opt == "--noise":
                cmd += ["--seed", "1"]
    elif kind in ("solver", "overlap"):
        if kind == "solver":
            deck, descs = fuzz_solvers.solver_deck(rng, read_text(path), stem, mut)
        else:
            deck, descs, expect = fuzz_solvers.overlap_deck(rng, read_text(path), stem, mut)
            if expect:
                case["expect"] = expect
        with open(os.path.join(case_dir, "deck.yaml"), "wb") as f:
            f.write(deck)
        for fn, data in referenced_files(read_text(path), path).items():
            os.makedirs(os.path.dirname(os.path.join(case_dir, fn)), exist_ok=True)
            with open(os.path.join(case_dir, fn), "wb") as f:
                f.write(data)
        # the reduced size and simulation.max_steps are in the deck
        cmd = [ballista, "run", os.path.join(case_dir, "deck.yaml"), "-o", out_dir, "--no-plots", "-q",
               "--threads", "1"]
    elif kind == "checkpoint":
        plan = fuzz_checkpoints.make(rng, stem, path, case_dir, ballista, mut, os.path.join(REPO, "examples"))
        case["plan"] = plan
        descs, cmd = list(plan["mutation"]), plan["first"]
    elif kind == "concurrent":
        plan, descs = fuzz_folders.make_concurrent(rng, stem, path, case_dir, ballista, mut,
                                                   os.path.join(REPO, "examples"))
        case["plan"] = plan
        cmd = plan["second"]
    elif kind == "userfile":
        plan, descs = fuzz_folders.make_userfile(rng, stem, path, case_dir, ballista, mut,
                                                 os.path.join(REPO, "examples"))
        case["plan"] = plan
        cmd = plan["cmds"][-1][1]
    elif kind == "models":
        argv, descs = models_case(rng, stem) if mut else (models_case(None, stem), [])
        cmd = [ballista, "models"] + argv
        if "--json" not in argv:
            cmd += ["--json", os.path.join(case_dir, "models.json")]
        os.makedirs(out_dir, exist_ok=True)
    else:
        raise ValueError(kind)
    case["mutation"] = descs
    case["cmd"] = cmd
    return case


# ---------------------------------------------------------------------------------------------
# Running and classifying
# ---------------------------------------------------------------------------------------------
# CSV columns where "nan" is the documented marker of a value that is not defined at that row
# (docs/deck.md, penetration section): the time since firing before the penetrator fires, the
# local-polynomial rates at the ends of the series, the channel radius of a bin with no target
# material. Anywhere else, and "inf" anywhere, is a non-finite result.
NAN_ALLOWED = {"history.csv": ("penetration_time",), "penetration.csv": ("rate", "cavity_rate"),
               "channel.csv": ("radius", "innermost_radius")}
NONFINITE_TOKEN = re.compile(r"(?<![A-Za-z0-9_])[-+]?(nan|inf|infinity)(?![A-Za-z0-9_])", re.IGNORECASE)
UNCAUGHT = ["terminate called", "what():", "Assertion `", "assertion failed", "AddressSanitizer",
            "runtime error:", "UndefinedBehaviorSanitizer", "Segmentation fault", "core dumped", "stack smashing",
            "double free", "free(): invalid", "malloc(): ", "corrupted size"]
# summary.json keys that are null when not applicable (no impact, no steady phase, no stages; a
# hole or tunnel with no material left to make a wall, or not reached yet).
NULL_OK = {"main_stage_start", "arrival_time", "stop_time", "steady_rate", "rate_over_hydrodynamic",
           "penetration_time", "min_dt_set_by", "entrance_diameter", "entrance_depth", "min_diameter", "mean_diameter",
           # holes.<layer>.jet_behind before the jet's front has passed the layer
           "time", "consumed_length", "remaining_length", "tip_velocity", "tip_segment", "tip_initial_velocity",
           # penetration.path_cells: the band covers the whole tunnel (and on every uniform grid)
           "coarser_from_depth",
           # tension.<material>: no point in tension yet, or none beyond the cohesive limit
           "most_tensile_time", "most_points_beyond_time", "first_beyond_time",
           # penetration.beyond_tunnel: no floor on the axis (perforated); no point beyond it
           "beyond_tunnel", "deepest",
           # penetration.convergence: a run that is not a level of its grid study, or of other physics,
           # nor a configuration it checked
           "checked", "level_cell", "level_value", "level_gap", "run_value", "within", "order", "richardson"}
# Also null in a penetration object with formed_jet true (a jet formed in the run): what only a rod's
# or a jet table's deck states is not known.
NULL_OK_FORMED_JET = {"impact_velocity", "penetrator_length", "hydrodynamic_rate", "hydrodynamic_depth",
                      "cells_across_radius", "jet_behind"}
# summary.json lists whose items are null when not applicable: holes.<layer>.diameters in a slice
# the layer has gone from.
NULL_OK_ITEMS = {"diameters"}


class _Bad(Exception):
    pass


def _json_bad(node, path, found, null_items=False, null_ok=frozenset()):
    if isinstance(node, dict):
        if node.get("formed_jet") is True:
            null_ok = null_ok | NULL_OK_FORMED_JET
        for k, v in node.items():
            if v is None and k not in NULL_OK and k not in null_ok:
                found.append(f"{path}.{k} = null")
            _json_bad(v, f"{path}.{k}", found, k in NULL_OK_ITEMS, null_ok)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            if v is None and not null_items:
                found.append(f"{path}[{i}] = null")
            _json_bad(v, f"{path}[{i}]", found, null_ok=null_ok)
    elif isinstance(node, float) and not math.isfinite(node):
        found.append(f"{path} = {node}")


def check_json_file(fn, found):
    try:
        with open(fn, encoding="utf-8", errors="replace") as f:
            text = f.read()
    except OSError as e:
        found.append(f"{os.path.basename(fn)}: unreadable ({e})")
        return

    def constant(c):
        found.append(f"{os.path.basename(fn)}: {c}")
        return float("nan")
    try:
        data = json.loads(text, parse_constant=constant)
    except ValueError as e:
        found.append(f"{os.path.basename(fn)}: not JSON ({e})")
        return
    _json_bad(data, os.path.basename(fn), found)


def check_outputs(stdout, out_dir, extra_json):
    found = []
    for line in stdout.splitlines():
        if line.startswith("[") or line.startswith("results in "):  # log lines, not results
            continue
        if "=" in line or re.match(r"^\s+\S+\s+\S", line):
            rhs = line.split("=", 1)[1] if "=" in line else line
            if NONFINITE_TOKEN.search(rhs):
                found.append(f"stdout: {line.strip()[:200]}")
    files = []
    if os.path.isdir(out_dir):
        for root, _, names in os.walk(out_dir):
            for n in names:
                files.append(os.path.join(root, n))
    for fn in extra_json:
        if os.path.exists(fn):
            files.append(fn)
    for fn in sorted(files):
        if fn.endswith(".json"):
            check_json_file(fn, found)
        elif fn.endswith(".csv"):
            try:
                with open(fn, encoding="utf-8", errors="replace") as f:
                    fcols = None
                    for ln, line in enumerate(f):
                        if ln == 0:
                            head = line.strip().split(",")
                            names = [f"F{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
                            if all(n in head for n in names):
                                fcols = [head.index(n) for n in names]
                        elif fcols and ln < 100000:
                            # a deformation gradient must stay invertible (J > 0) in a successful run
                            try:
                                c = line.strip().split(",")
                                F = [float(c[k]) for k in fcols]
                                J = (F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6])
                                     + F[2] * (F[3] * F[7] - F[4] * F[6]))
                                if math.isfinite(J) and J <= 1e-300:
                                    found.append(f"{os.path.basename(fn)}:{ln + 1}: det F = {J:g}")
                                    fcols = None
                            except (ValueError, IndexError):
                                pass
                        if ln == 0:
                            allowed = {i for i, h in enumerate(line.strip().split(","))
                                       if h in NAN_ALLOWED.get(os.path.basename(fn), ())}
                            continue
                        cells = line.strip().split(",")
                        m = re.search(r"(^|,)null(,|$)", line.strip()) or any(
                            NONFINITE_TOKEN.fullmatch(c) and not (i in allowed and c.lower() == "nan")
                            for i, c in enumerate(cells))
                        if m:
                            found.append(f"{os.path.relpath(fn, out_dir) if fn.startswith(out_dir) else fn}:"
                                         f"{ln + 1}: {line.strip()[:200]}")
                            break
            except OSError:
                pass
    return found


def _dir_size(path):
    total = 0
    for root, _, names in os.walk(path):
        for n in names:
            try:
                total += os.lstat(os.path.join(root, n)).st_size
            except OSError:
                pass
    return total


def _limits(a):
    mem = a.mem_limit_mb * 1024 * 1024

    def limits():
        if mem > 0:  # 0: no address-space limit (AddressSanitizer reserves terabytes of shadow memory)
            resource.setrlimit(resource.RLIMIT_AS, (mem, mem))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
        fs = a.max_output_mb * 1024 * 1024
        resource.setrlimit(resource.RLIMIT_FSIZE, (fs, fs))
    return limits


def start_cmd(cmd, cwd, a, so_path, se_path):
    """Start cmd in its own process group (session) under the per-case limits; returns a handle for
    finish_cmd. handle["paused"] holds seconds not counted against --time-limit (SIGSTOP)."""
    env = dict(os.environ, OMP_WAIT_POLICY="passive", OMP_NUM_THREADS="1")
    so, se = open(so_path, "wb"), open(se_path, "wb")
    p = subprocess.Popen(cmd, stdout=so, stderr=se, stdin=subprocess.DEVNULL, cwd=cwd, env=env,
                         start_new_session=True, preexec_fn=_limits(a))
    return {"p": p, "t0": time.monotonic(), "so": so, "se": se, "so_path": so_path, "se_path": se_path,
            "paused": 0.0}


def kill_group(h):
    try:
        os.killpg(h["p"].pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    try:
        os.killpg(h["p"].pid, signal.SIGCONT)  # a stopped group dies only when continued
    except ProcessLookupError:
        pass


def finish_cmd(h, a, watch_dir):
    """Wait for a started command under the time limit and the output-size limit of watch_dir (then
    its process group is killed). Returns the raw outcome: rc, status (hang, runaway_output or
    None), detail, stdout, stderr, stderr_len, wall."""
    p, t0 = h["p"], h["t0"]
    status, detail = None, ""
    next_check = t0 + 1.0
    while True:
        try:
            p.wait(timeout=0.05 if time.monotonic() - t0 < 1 else 0.25)
            break
        except subprocess.TimeoutExpired:
            pass
        now = time.monotonic()
        if now - t0 - h["paused"] > a.time_limit:
            status, detail = "hang", f"no exit after {a.time_limit:g} s"
        elif now >= next_check:
            next_check = now + 1.0
            if _dir_size(watch_dir) > a.max_output_mb * 1024 * 1024:
                status, detail = "runaway_output", f"output over {a.max_output_mb} MB"
        if status:
            kill_group(h)
            p.wait()
            break
    wall = time.monotonic() - t0 - h["paused"]
    h["so"].close()
    h["se"].close()
    with open(h["so_path"], "rb") as f:
        stdout = f.read(2_000_000).decode("utf-8", "replace")
    with open(h["se_path"], "rb") as f:
        stderr = f.read(2_000_000).decode("utf-8", "replace")
    se_size = os.path.getsize(h["se_path"])
    stderr_len = len(stderr) if se_size < 2_000_000 else se_size
    return {"rc": p.returncode, "status": status, "detail": detail, "stdout": stdout, "stderr": stderr,
            "stderr_len": stderr_len, "wall": wall}


def classify(raw, a, out_dir, case=None, extra_json=()):
    """The outcome class of a finished command (see the module docstring). case: its "mutation"
    claims ("must be rejected") and "expect_rows" are checked on exit 0."""
    rc, stdout, stderr = raw["rc"], raw["stdout"], raw["stderr"]
    status, detail = raw["status"], raw["detail"]
    if status is None:
        if any(s in stderr for s in UNCAUGHT):
            status = "uncaught"
            detail = next(s for s in UNCAUGHT if s in stderr)
        elif "bad_alloc" in stderr or "Cannot allocate memory" in stderr:
            # the address-space limit (--mem-limit-mb) was hit: either an unbounded allocation or a
            # size check that missed (one that honours getrlimit(RLIMIT_AS) refuses the deck cleanly)
            status, detail = "out_of_memory", f"allocation failed under {a.mem_limit_mb} MB (exit {rc})"
        elif rc < 0:
            try:
                detail = signal.Signals(-rc).name
            except ValueError:
                detail = f"signal {-rc}"
            status = "signal"
            if -rc == signal.SIGXFSZ:
                status, detail = "runaway_output", "file size limit (SIGXFSZ)"
        elif rc == 0:
            bad = check_outputs(stdout, out_dir, list(extra_json))
            ignored = [m for m in (case or {}).get("mutation", []) if "must be rejected" in m]
            if case and "expect_rows" in case:
                sec, key, n = case["expect_rows"]
                try:
                    with open(os.path.join(out_dir, "summary.json")) as f:
                        got = json.load(f)[sec][key]
                    if got != n:
                        ignored.append(f"table has {n} rows but summary {sec}.{key} = {got} (rows dropped)")
                except (OSError, ValueError, KeyError, TypeError):
                    pass
            if bad:
                status, detail = "nonfinite_success", "; ".join(bad[:5])
                if ignored:
                    detail += " | also exit 0 although: " + "; ".join(ignored)[:300]
            elif ignored:
                status, detail = "ignored_input", "exit 0 although: " + "; ".join(ignored)[:500]
            else:
                status = "ok"
        else:
            if not (stderr.strip() or stdout.strip()):
                status, detail = "silent_failure", f"exit {rc} without a message"
            else:
                status = "rejected"
        if status in ("ok", "rejected") and raw["stderr_len"] > a.max_error_chars:
            status, detail = "error_too_long", f"stderr {raw['stderr_len']} characters"
    msg = (stderr.strip() or stdout.strip()).splitlines()
    return {"class": status, "detail": detail[:1000], "exit": rc, "wall": round(raw["wall"], 3),
            "message": (msg[-1] if msg else "")[:300]}


def run_cmd(cmd, cwd, a, tag, watch_dir, out_dir, case=None):
    """Run one command to its end and classify it; stdout/stderr go to cwd/<tag>stdout.txt and
    <tag>stderr.txt. Returns (result, raw)."""
    h = start_cmd(cmd, cwd, a, os.path.join(watch_dir, f"{tag}stdout.txt"), os.path.join(watch_dir, f"{tag}stderr.txt"))
    raw = finish_cmd(h, a, watch_dir)
    return classify(raw, a, out_dir, case), raw


RUNNER = types.SimpleNamespace(start_cmd=start_cmd, finish_cmd=finish_cmd, classify=classify, run_cmd=run_cmd)
EXECUTE = {"checkpoint": fuzz_checkpoints.execute, "concurrent": fuzz_folders.execute_concurrent,
           "userfile": fuzz_folders.execute_userfile}


def run_case(case, case_dir, a):
    if case["kind"] in EXECUTE:  # several commands: the module runs and classifies them
        return EXECUTE[case["kind"]](case, case_dir, a, RUNNER)
    h = start_cmd(case["cmd"], case_dir, a, os.path.join(case_dir, "stdout.txt"), os.path.join(case_dir, "stderr.txt"))
    raw = finish_cmd(h, a, case_dir)
    res = classify(raw, a, os.path.join(case_dir, "out"), case, [os.path.join(case_dir, "models.json")])
    if case.get("expect"):  # overlap:<stem>: overlapping bodies must be refused, touching ones not
        new = fuzz_solvers.expectation_class(case, res, raw["stderr"], raw["stdout"])
        if new:
            res["class"], res["detail"] = new[0], new[1][:1000]
    return res


def repro_script(case, case_dir):
    """A shell script that reruns the case from its own folder (the folder can be copied anywhere;
    BALLISTA=path overrides the binary)."""
    args = [("./" + os.path.relpath(c, case_dir)) if c.startswith(case_dir + os.sep) else c for c in case["cmd"][1:]]
    cmd = " ".join(shlex.quote(c) for c in args)
    head = "; ".join(m[:200] for m in case["mutation"]).replace("\n", " ")
    return ("#!/bin/sh\n# fuzz case {idx} ({src}): {mut}\n# class {cls}: {det}\n"
            "B=${{BALLISTA:-{b}}}\ncd \"$(dirname \"$0\")\" && rm -rf out models.json && mkdir -p out\n"
            "timeout 60 \"$B\" {cmd}\necho \"exit $?\"\n").format(
        idx=case["index"], src=case["source"], mut=head, cls=case["class"],
        det=case["detail"].replace("\n", " ")[:300], b=shlex.quote(case["cmd"][0]), cmd=cmd)


def do_case(index, a, sources, cases_root):
    baseline = None
    if isinstance(index, tuple):  # (negative index, source): the unmutated source
        index, baseline = index
    case_dir = os.path.join(cases_root, f"{index:06d}" if index >= 0 else f"baseline{-index:03d}")
    if os.path.exists(case_dir):
        shutil.rmtree(case_dir)
    case = make_case(index, a.seed, sources, case_dir, a.ballista, baseline)
    case.update(run_case(case, case_dir, a))
    if baseline and case["class"] != "ok":  # the unmutated, reduced source must run cleanly
        case["detail"] = f"unmutated source gave {case['class']}: {case['detail']} {case['message']}"
        case["class"] = "baseline_failed"
    if case["class"] in FAILURE_CLASSES or a.keep_all:
        out = os.path.join(case_dir, "out")
        # keep inputs and text outputs; drop bulky particle files
        for root, _, names in os.walk(out):
            for n in names:
                if n.endswith(".h5"):
                    os.remove(os.path.join(root, n))
        kind = case["kind"]
        if kind == "checkpoint":
            fuzz_checkpoints.cleanup_kept(case_dir)
            script = fuzz_checkpoints.repro(case, case_dir, os.path.dirname(os.path.abspath(__file__)))
        elif kind == "concurrent":
            script = fuzz_folders.repro_concurrent(case, case_dir, a.ballista)
        elif kind == "userfile":
            fuzz_folders.keep_userfiles(case, case_dir)
            script = fuzz_folders.repro_userfile(case, case_dir, a.ballista)
        else:
            script = repro_script(case, case_dir)
        with open(os.path.join(case_dir, "repro.sh"), "w") as f:
            f.write(script)
        os.chmod(os.path.join(case_dir, "repro.sh"), 0o755)
        with open(os.path.join(case_dir, "case.json"), "w") as f:
            json.dump(case, f, indent=1)
    else:
        shutil.rmtree(case_dir, ignore_errors=True)
    return case


def write_summary(a, results, wall, done, total):
    counts = {c: 0 for c in ALL_CLASSES}
    per_source = {}
    exits = {}
    for r in results:
        counts[r["class"]] += 1
        ps = per_source.setdefault(r["source"], {})
        ps[r["class"]] = ps.get(r["class"], 0) + 1
        exits[str(r["exit"])] = exits.get(str(r["exit"]), 0) + 1
    failures = sorted((r for r in results if r["class"] in FAILURE_CLASSES), key=lambda r: r["index"])
    summary = {"seed": a.seed, "cases": total, "completed": done, "wall_time_s": round(wall, 1),
               "ballista": a.ballista, "time_limit_s": a.time_limit, "counts": counts, "exit_codes": exits,
               "per_source": per_source,
               "failures": [{"index": r["index"], "class": r["class"], "source": r["source"],
                             "detail": r["detail"], "mutation": r["mutation"],
                             "dir": os.path.join(a.out, "cases", f"{r['index']:06d}"),
                             "cmd": " ".join(shlex.quote(c) for c in r["cmd"])[:2000]} for r in failures]}
    with open(os.path.join(a.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    md = [f"# Fuzz summary", "", f"seed {a.seed}, {done} of {total} cases, {wall:.0f} s, ballista `{a.ballista}`",
          "", "| class | cases |", "|---|---|"]
    md += [f"| {c} | {counts[c]} |" for c in ALL_CLASSES]
    md += ["", "| source | " + " | ".join(ALL_CLASSES) + " |", "|---" * (len(ALL_CLASSES) + 1) + "|"]
    for s in sorted(per_source):
        md.append(f"| {s} | " + " | ".join(str(per_source[s].get(c, 0)) for c in ALL_CLASSES) + " |")
    md += ["", "## Failures", ""]
    for r in failures:
        md.append(f"- case {r['index']} **{r['class']}** ({r['source']}): {'; '.join(m[:120] for m in r['mutation'])}"
                  f" -- {r['detail'][:300]}\n  reproduce: `{os.path.join(a.out, 'cases', format(r['index'], '06d'), 'repro.sh')}`")
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    return counts


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ballista", default=os.path.join(REPO, "build", "ballista"))
    ap.add_argument("--out", default="out/fuzz")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=200)
    ap.add_argument("--first", type=int, default=0, help="index of the first case (cases first..first+N-1)")
    ap.add_argument("--only", type=int, nargs="*", help="run only these case indices")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--time-limit", type=float, default=20.0, help="seconds per case before it counts as a hang")
    ap.add_argument("--mem-limit-mb", type=int, default=3072,
                    help="address-space limit per case (0: none, e.g. for a sanitizer build)")
    ap.add_argument("--max-output-mb", type=int, default=300, help="output size per case before runaway_output")
    ap.add_argument("--max-error-chars", type=int, default=4000,
                    help="longest acceptable stderr in characters (an echoed bad value cut to ~2000 fits)")
    ap.add_argument("--source", action="append", help="only sources whose name contains this (repeatable)")
    ap.add_argument("--kinds", help="only these source kinds, comma-separated: " + ", ".join(
        list(KIND_WEIGHTS) + list(NEW_KIND_WEIGHTS)) + "; 'old' for the first five, 'new' for issue 35's")
    ap.add_argument("--baseline", action="store_true",
                    help="also run every source unmutated first; each must be ok (else class baseline_failed)")
    ap.add_argument("--keep-all", action="store_true", help="keep every case's folder, not only failures")
    ap.add_argument("--progress", type=int, default=0, help="print the counts every N cases")
    a = ap.parse_args()
    a.ballista = os.path.abspath(a.ballista)
    a.out = os.path.abspath(a.out)
    if not os.access(a.ballista, os.X_OK):
        sys.exit(f"fuzz_decks: no executable {a.ballista}")
    sources = discover_sources()
    if a.kinds:
        want = set()
        for k in a.kinds.split(","):
            k = k.strip()
            if k == "old":
                want |= set(KIND_WEIGHTS)
            elif k == "new":
                want |= set(NEW_KIND_WEIGHTS)
            elif k in KIND_WEIGHTS or k in NEW_KIND_WEIGHTS:
                want.add(k)
            else:
                sys.exit(f"fuzz_decks: unknown kind {k!r} in --kinds")
        sources = [s for s in sources if s[0] in want]
    if a.source:
        sources = [s for s in sources if any(x in f"{s[0]}:{s[1]}" for x in a.source)]
        if not sources:
            sys.exit("fuzz_decks: no source matches --source")
    os.makedirs(a.out, exist_ok=True)
    cases_root = os.path.join(a.out, "cases")
    if not a.only and os.path.isdir(cases_root):  # a full run starts clean: no stale reproducers
        shutil.rmtree(cases_root)
    os.makedirs(cases_root, exist_ok=True)
    indices = a.only if a.only else list(range(a.first, a.first + a.cases))
    if a.baseline:
        indices = [(-(k + 1), s) for k, s in enumerate(sources)] + indices
    results, lock = [], threading.Lock()
    t0 = time.monotonic()
    jsonl = open(os.path.join(a.out, "results.jsonl"), "w")
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        futs = [ex.submit(do_case, i, a, sources, cases_root) for i in indices]
        for fut in concurrent.futures.as_completed(futs):
            r = fut.result()
            with lock:
                results.append(r)
                rec = {k: r[k] for k in ("index", "source", "class", "exit", "wall", "detail", "message",
                                         "mutation")}
                jsonl.write(json.dumps(rec) + "\n")
                jsonl.flush()
                if r["class"] in FAILURE_CLASSES:
                    print(f"FAIL case {r['index']} {r['class']} {r['source']}: {'; '.join(r['mutation'])[:200]}"
                          f" -- {r['detail'][:200]}", flush=True)
                if a.progress and len(results) % a.progress == 0:
                    write_summary(a, results, time.monotonic() - t0, len(results), len(indices))
                    c = {k: v for k, v in write_summary(a, results, time.monotonic() - t0, len(results),
                                                        len(indices)).items() if v}
                    print(f"[{len(results)}/{len(indices)} {time.monotonic() - t0:.0f} s] {c}", flush=True)
    jsonl.close()
    counts = write_summary(a, results, time.monotonic() - t0, len(results), len(indices))
    print(f"fuzz_decks: {len(results)} cases in {time.monotonic() - t0:.1f} s: " +
          ", ".join(f"{c} {n}" for c, n in counts.items() if n))
    print(f"summary: {os.path.join(a.out, 'summary.md')}")
    return 1 if any(counts[c] for c in FAILURE_CLASSES) else 0


if __name__ == "__main__":
    sys.exit(main())
