#!/usr/bin/python3
"""Throughput of ballista.drive (the Python module's single material point, docs/python.md):
steps per second over whole calls (deck parse, material set-up, the steps, the history array),
as an optimiser sees them. Median of REPEATS calls per case; one thread (the driver is serial).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_drive_bench.py [REPEATS]
"""
import os
import statistics
import sys
import time

import ballista

HERE = os.path.dirname(os.path.abspath(__file__))
J2 = os.path.join(HERE, "..", "examples", "drive_uniaxial_stress_j2.yaml")
JC = {
    "materials": {"cu": {"preset": "copper_ofhc_jc", "jc_c": 0.0, "taylor_quinney": 0.0,
                         "failure": {"criterion": "none"}}},
    "drive": {"legs": [{"duration": 1.0, "steps": 600, "strain": {"11": 0.5}, "stress": {"22": 0, "33": 0}}]},
}
STRAIN = {
    "materials": {"cu": {"preset": "copper_ofhc_jc"}},
    "drive": {"legs": [{"duration": 1e-4, "steps": 1000, "strain": {"11": -0.1}}]},
}


def bench(name, deck, repeats):
    rates = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        h = ballista.drive(deck)
        wall = time.perf_counter() - t0
        rates.append(h.steps / wall)
    print(f"{name:<44} {h.steps:6d} steps/call  {statistics.median(rates):10.4g} steps/s "
          f"(min {min(rates):.4g}, max {max(rates):.4g})")


if __name__ == "__main__":
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 50
    print(f"ballista {ballista.__version__} ({ballista.commit}), {repeats} calls per case")
    bench("J2 uniaxial stress (example deck, Newton)", J2, repeats)
    bench("Johnson-Cook copper uniaxial stress (Newton)", JC, repeats)
    bench("Johnson-Cook copper uniaxial strain", STRAIN, repeats)
