#!/usr/bin/env python3
"""`ballista` as a program (tests/cli/CMakeLists.txt).

1. OpenMP wait policy: with neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT set, ballista re-executes
   itself once with the chosen policy (src/core/threads.hpp, kOmpWaitDefault). libgomp reports the
   spin count it actually uses when OMP_DISPLAY_ENV=verbose (one report per process image), so the
   check reads the policy in effect from libgomp itself, not from our code. A user's policy is left
   alone (one image, the user's spin count); the runs of a sweep inherit the policy.
2. --threads 100000 and simulation.threads above the cores: clamped, with a warning naming both;
   under -q nothing is printed and the warning is in summary.json "warnings". Without -q the log
   (start banner, progress, warnings) is on standard error and the report on standard output.
3. --seed outside 0..2^63-1 is rejected with the message of the deck key drive.seed.
4. Provenance: --version and summary.json `build` name the commit the binary was built from
   (`git describe` of the source tree, which `make test` has just rebuilt).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys

# kOmpWaitDefault = OMP_WAIT_POLICY=passive: libgomp then waits 0 spins before it sleeps.
DEFAULT_SPINCOUNT = "0"
LIBGOMP_UNSET_SPINCOUNT = "300000"  # libgomp's own default when nothing is set (the spin trap)
LIBGOMP_ACTIVE_SPINCOUNT = "30000000000"  # OMP_WAIT_POLICY=active


def fail(msg):
    sys.exit("FAIL: " + msg)


def clean_env(**extra):
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "BALLISTA_OMP_REEXEC", "OMP_DISPLAY_ENV")}
    env.update(extra)
    return env


def run(cmd, expect, env):
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != expect:
        fail(f"{' '.join(cmd)} exited {p.returncode}, expected {expect}:\n{p.stdout}\n{p.stderr}")
    return p


def omp_reports(text):
    """The OMP_DISPLAY_ENV reports in a process's output, each as a dict of its variables."""
    blocks = re.findall(r"OPENMP DISPLAY ENVIRONMENT BEGIN\n(.*?)OPENMP DISPLAY ENVIRONMENT END", text, re.S)
    return [dict(re.findall(r"^\s*(\w+) = '([^']*)'", b, re.M)) for b in blocks]


def check_wait_policy(b, examples, out):
    # Default: two images (the first one's libgomp has already read the environment when main()
    # re-executes), the last one with the chosen spin count; argv and the user's other variables
    # (OMP_NUM_THREADS, OMP_DISPLAY_ENV itself) reach the second image.
    p = run([b, "--version"], 0, clean_env(OMP_DISPLAY_ENV="verbose", OMP_NUM_THREADS="1"))
    reps = omp_reports(p.stderr)
    if len(reps) != 2:
        fail(f"expected 2 libgomp reports (one re-exec), got {len(reps)}:\n{p.stderr}")
    if reps[0].get("GOMP_SPINCOUNT") != LIBGOMP_UNSET_SPINCOUNT:
        fail(f"first image: GOMP_SPINCOUNT {reps[0].get('GOMP_SPINCOUNT')}, expected libgomp's default")
    if reps[1].get("GOMP_SPINCOUNT") != DEFAULT_SPINCOUNT:
        fail(f"policy in effect: GOMP_SPINCOUNT {reps[1].get('GOMP_SPINCOUNT')}, expected {DEFAULT_SPINCOUNT}")
    if reps[1].get("OMP_NUM_THREADS") != "1":
        fail(f"the environment was not kept across the re-exec: {reps[1]}")
    if not p.stdout.startswith("ballista "):
        fail(f"argv was not kept across the re-exec: {p.stdout!r}")

    # The user's choice is left alone: one image, the user's spin count.
    for var, value, spin in (("OMP_WAIT_POLICY", "active", LIBGOMP_ACTIVE_SPINCOUNT),
                             ("GOMP_SPINCOUNT", "12345", "12345"),
                             ("OMP_WAIT_POLICY", "passive", "0")):
        p = run([b, "--version"], 0, clean_env(OMP_DISPLAY_ENV="verbose", **{var: value}))
        reps = omp_reports(p.stderr)
        if len(reps) != 1 or reps[0].get("GOMP_SPINCOUNT") != spin:
            fail(f"{var}={value}: expected one libgomp report with GOMP_SPINCOUNT {spin}, got {reps}")

    # A sweep's runs inherit the policy: each runs as one image with the chosen spin count.
    sweep_out = os.path.join(out, "sweep")
    run([b, "sweep", os.path.join(examples, "elastic_disks.yaml"), "--vary",
         "materials.soft.youngs_modulus=1000,2000", "--jobs", "2", "-o", sweep_out, "-q",
         "--set", "grid.cell_size=0.05", "--set", "simulation.end_time=0.05"], 0,
        clean_env(OMP_DISPLAY_ENV="verbose"))
    for k in range(2):
        with open(os.path.join(sweep_out, f"run_{k}", "log.txt")) as f:
            reps = omp_reports(f.read())
        if len(reps) != 1 or reps[0].get("GOMP_SPINCOUNT") != DEFAULT_SPINCOUNT:
            fail(f"sweep run_{k}: expected one libgomp report with GOMP_SPINCOUNT {DEFAULT_SPINCOUNT}, got {reps}")


def check_thread_clamp(b, examples, out):
    cores = len(os.sched_getaffinity(0))  # omp_get_num_procs() counts the same (the affinity mask)
    deck = os.path.join(examples, "elastic_disks.yaml")
    small = ["--set", "grid.cell_size=0.05", "--set", "simulation.end_time=0.05", "-q"]
    for extra, source, n in ((["--threads", "100000"], "--threads", 100000),
                             (["--set", "simulation.threads=4096"], "simulation.threads", 4096)):
        o = os.path.join(out, "clamp_" + source.strip("-").replace(".", "_"))
        p = run([b, "run", deck, "-o", o] + small + extra, 0, clean_env())
        want = f"{source} = {n} is more than the {cores} cores available: using {cores} threads"
        # -q: the warning is not printed, it is recorded with the results.
        if p.stdout or p.stderr:
            fail(f"-q printed something other than errors:\n{p.stdout}{p.stderr}")
        with open(os.path.join(o, "summary.json")) as f:
            summary = json.load(f)
        if want not in summary.get("warnings", []):
            fail(f"expected the warning '{want}' in summary.json warnings: {summary.get('warnings')}")
        threads = summary["statistics"]["threads"]
        if threads != cores:
            fail(f"{source} = {n}: the run used {threads} threads, expected {cores}")
    # Within the cores: no warning, the count asked for.
    o = os.path.join(out, "threads_1")
    p = run([b, "run", deck, "-o", o, "--threads", "1"] + small, 0, clean_env())
    if "cores available" in p.stdout + p.stderr:
        fail(f"--threads 1 warned:\n{p.stdout}{p.stderr}")
    with open(os.path.join(o, "summary.json")) as f:
        if json.load(f)["statistics"]["threads"] != 1:
            fail("--threads 1 did not run on 1 thread")


def check_console(b, examples, out):
    """Results on standard output, diagnostics on standard error: a run's log lines (start banner,
    progress, warnings) go to stderr, its report (headline numbers, probes, where the results are)
    to stdout; the banner names the solver and counts the particles."""
    deck = os.path.join(examples, "elastic_disks.yaml")
    o = os.path.join(out, "console")
    p = run([b, "run", deck, "-o", o, "--threads", "1", "--set", "grid.cell_size=0.05", "--set",
             "simulation.end_time=0.05"], 0, clean_env())
    if "[info]" in p.stdout or "[warning]" in p.stdout:
        fail(f"log lines on standard output:\n{p.stdout}")
    if not re.search(r"mpm solver, .*; [\d,]+ particles: ", p.stderr):
        fail(f"no start banner (solver, particle counts) on standard error:\n{p.stderr[:2000]}")
    if "memory after set-up" not in p.stderr or "steps: about" not in p.stderr:
        fail(f"the start banner lacks the memory or the step estimate:\n{p.stderr[:2000]}")
    if not p.stdout.startswith("completed: ") or "results in " not in p.stdout:
        fail(f"the run's report is not on standard output:\n{p.stdout}")


def check_seed(b, examples, out):
    deck = os.path.join(examples, "drive_a1_frame_indifference.yaml")
    base = [b, "drive", deck, "--set", "drive.substeps=10", "--noise", "0.01", "-q"]

    def error_line(p):
        return p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ""

    for bad in ("99999999999999999999", "9223372036854775808", "-1", "1.5", ""):
        o = os.path.join(out, "seed_bad")
        cli = run(base + ["-o", o, "--seed", bad], 2, clean_env())
        deck_key = run(base + ["-o", o, "--set", "drive.seed=" + (bad or "''")], 2, clean_env())
        # The same message as the deck key, which names the key and the value given.
        if error_line(cli) != error_line(deck_key):
            fail(f"--seed {bad}: '{error_line(cli)}' differs from drive.seed's '{error_line(deck_key)}'")
        if "drive.seed" not in error_line(cli) or bad not in error_line(cli):
            fail(f"--seed {bad}: the error does not name drive.seed and the value: {error_line(cli)}")
    for good in ("0", "42", "9223372036854775807"):
        o = os.path.join(out, "seed_" + good)
        run(base + ["-o", o, "--seed", good], 0, clean_env())
        with open(os.path.join(o, "resolved.yaml")) as f:
            text = f.read()
        if not re.search(r"^\s*seed: " + good + r"\s*$", text, re.M):
            fail(f"--seed {good}: resolved.yaml does not record seed {good}:\n{text}")


def check_provenance(b, out):
    p = run([b, "--version"], 0, clean_env())
    m = re.match(r"ballista (\S+) \((\S+)\)$", p.stdout.strip())
    if not m:
        fail(f"--version does not read 'ballista VERSION (COMMIT)': {p.stdout!r}")
    version, commit = m.groups()
    source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    g = subprocess.run(["git", "-C", source, "describe", "--always", "--abbrev=12"], capture_output=True, text=True)
    if g.returncode == 0:
        # The commit, not the dirty mark: a tree edited after the build is still the same commit.
        if commit.removesuffix("-dirty") != g.stdout.strip():
            fail(f"--version names {commit}, the source tree is at {g.stdout.strip()}")
    elif commit != "unknown":
        fail(f"outside git the commit should read 'unknown', got {commit}")
    with open(os.path.join(out, "threads_1", "summary.json")) as f:
        summary = json.load(f)
    build = summary.get("build", {})
    if {k: build.get(k) for k in ("version", "commit")} != {"version": version, "commit": commit}:
        fail(f"summary.json build {build}, --version says {version} ({commit})")
    # The instruction set: the compiler's generic target, -march=native as resolved at build time,
    # or the -march of the build's own flags.
    if not re.fullmatch(r"native \([\w.-]+\)|[\w.-]+", str(build.get("cpu_target"))):
        fail(f"summary.json build.cpu_target reads {build.get('cpu_target')!r}")
    # The processor the run ran on, as the kernel names it.
    cpu = "unknown"
    if os.path.exists("/proc/cpuinfo"):
        with open("/proc/cpuinfo") as f:
            names = [ln.split(":", 1)[1].strip() for ln in f if ln.startswith("model name")]
        cpu = names[0] if names else "unknown"
    if summary.get("statistics", {}).get("cpu") != cpu:
        fail(f"summary.json statistics.cpu reads {summary.get('statistics', {}).get('cpu')!r}, /proc/cpuinfo {cpu!r}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ballista", required=True)
    ap.add_argument("--examples", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(a.out)
    check_wait_policy(a.ballista, a.examples, a.out)
    check_thread_clamp(a.ballista, a.examples, a.out)
    check_console(a.ballista, a.examples, a.out)
    check_seed(a.ballista, a.examples, a.out)
    check_provenance(a.ballista, a.out)
    print("ok")


if __name__ == "__main__":
    main()
