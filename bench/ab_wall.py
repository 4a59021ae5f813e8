#!/usr/bin/python3
"""Time two whole commands alternately (A B A B ...) and report their wall times and the ratio A/B.

A ratio between two builds (or between Ballista and a peer) is only meaningful when both ran on
the same machine in the same minutes: this machine's speed drifts by +-20 % from one hour to the
next. Running the two in turn and taking the ratio pair by pair keeps the drift out of the ratio.
Each run's wall time is measured from the command's start to its exit (start-up and set-up
included); the commands' output is discarded. Prints every pair, then min / median / max of each
command and of the pairwise ratio A/B (quote the median).

  bench/ab_wall.py -n 3 --warmup 1 \\
      --a "build/ballista run DECK -o /tmp/a -q --no-plots --overwrite --threads 2" \\
      --b "BASE/ballista run DECK -o /tmp/b -q --no-plots --overwrite --threads 2"

The commands are split as a shell splits words (shlex), and run without a shell.
"""
import argparse
import shlex
import statistics
import subprocess
import sys
import time


def run(cmd):
    t0 = time.monotonic()
    r = subprocess.run(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - t0, r.returncode


def spread(xs):
    return f"{min(xs):.3f} / {statistics.median(xs):.3f} / {max(xs):.3f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", required=True, help="command A (the change)")
    ap.add_argument("--b", required=True, help="command B (the base, or the peer)")
    ap.add_argument("-n", type=int, default=3, help="pairs timed (default 3)")
    ap.add_argument("--warmup", type=int, default=1, help="pairs run first and not timed (default 1)")
    a = ap.parse_args()
    A, B = shlex.split(a.a), shlex.split(a.b)
    for _ in range(a.warmup):
        run(A)
        run(B)
    ta, tb = [], []
    for i in range(a.n):
        wa, ra = run(A)
        wb, rb = run(B)
        ta.append(wa)
        tb.append(wb)
        print(f"pair {i + 1}: A {wa:.3f} s (exit {ra}), B {wb:.3f} s (exit {rb}), A/B {wa / wb:.3f}", flush=True)
        if ra or rb:
            print("a command failed: the figures are not comparable", file=sys.stderr)
    print(f"A wall (min / median / max): {spread(ta)} s")
    print(f"B wall (min / median / max): {spread(tb)} s")
    print(f"A/B pair by pair (min / median / max): {spread([x / y for x, y in zip(ta, tb)])}")


if __name__ == "__main__":
    main()
