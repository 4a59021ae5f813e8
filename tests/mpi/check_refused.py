#!/usr/bin/env python3
"""What does not run on several MPI ranks yet must be refused before anything runs, with a message
that names it (issue 16, docs/parallel.md), not run redundantly on every rank or hang.

  check_refused.py BALLISTA EXAMPLES_DIR WORKDIR
"""
import os, shutil, subprocess, sys

CASES = [
    # (deck, extra arguments, text the error must contain)
    ("pd_lps_kalthoff_winkler.yaml", ["--set", "grid.cell_size=0.005", "--set", "peridynamics.yield_stress=1e9"],
     "the state-based plasticity runs on one MPI rank"),
]


def main():
    ballista, examples, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    failures = []
    for k, (deck, extra, text) in enumerate(CASES):
        cmd = ["mpirun", "--oversubscribe", "--allow-run-as-root", "-np", "2", ballista, "run",
               os.path.join(examples, deck), "-o", os.path.join(work, str(k)), "-q", "--threads", "1"] + extra
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=100)
        if r.returncode == 0 or text not in r.stdout:
            failures.append(f"{deck} {' '.join(extra)}: exit {r.returncode}, expected an error containing "
                            f"'{text}'; output:\n{r.stdout[-1500:]}")
        else:
            print(f"refused as expected: {deck} {' '.join(extra)}")
    if failures:
        sys.exit("\n".join(failures))
    print("OK")


if __name__ == "__main__":
    main()
