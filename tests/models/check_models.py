#!/usr/bin/env python3
"""End-to-end check of `ballista models` (tests/models/CMakeLists.txt)."""
import argparse
import json
import math
import os
import subprocess
import sys

MODELS = ["birkhoff", "particulated-jet", "pack-evans", "eichelberger", "tate", "gladkikh", "grove", "harvey",
          "orphal-anderson", "orphal-anderson-fit", "pack-evans-fit"]


def run(cmd, expect_ok=True):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if expect_ok and p.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {p.returncode}: {p.stderr}")
    if not expect_ok and p.returncode == 0:
        sys.exit(f"FAIL: {' '.join(cmd)} succeeded but should have failed")
    # make test-sanitize: a UBSan abort exits non-zero too (ASan reports go to files there).
    if "runtime error:" in p.stderr:
        sys.exit(f"FAIL: {' '.join(cmd)}: UndefinedBehaviorSanitizer report:\n{p.stderr}")
    return p


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ballista", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    b = a.ballista

    listing = run([b, "models", "list"]).stdout
    for m in MODELS:
        if not any(line.startswith(m + "  (") for line in listing.splitlines()):
            sys.exit(f"FAIL: model {m} missing from 'ballista models list'")

    # Thesis Table 5.3, rows 3 and 5 (sandstone 2300 kg/m^3): hydrodynamic depth 21.27 and 15.04 cm,
    # printed to 0.01 cm; U_h = V / (1 + sqrt(rho_t/rho_p)) at V = 3300 m/s (§5.2).
    rows = [(19235.0, 0.07354, 0.2127), (38470.0, 0.03678, 0.1504)]
    for rho, L, P_table in rows:
        js = os.path.join(a.out, f"birkhoff_{int(rho)}.json")
        run([b, "models", "birkhoff", "--param", f"L={L}", "--param", f"rho_p={rho}", "--param", "rho_t=2300",
             "--velocities", "3300,3900", "--json", js])
        d = json.load(open(js))
        assert d["model"] == "birkhoff" and d["units"]["P"] == "m" and len(d["results"]) == 2, d
        for r in d["results"]:
            out, V = r["outputs"], r["params"]["V"]
            if abs(out["P"] - P_table) > 0.5e-4 + 0.5e-5 * math.sqrt(rho / 2300):  # printed rounding (L and P)
                sys.exit(f"FAIL: birkhoff P = {out['P']} m, Table 5.3 {P_table} m")
            U_ref = V / (1 + math.sqrt(2300 / rho))
            if abs(out["U"] - U_ref) > 1e-12 * U_ref:
                sys.exit(f"FAIL: birkhoff U = {out['U']} m/s, expected {U_ref}")

    # Tate: the RK4 depth equals the Walters-Segletes exact depth (unit test: ~1e-14 relative).
    js = os.path.join(a.out, "tate.json")
    run([b, "models", "tate", "-p", "L=0.1", "-p", "rho_p=17600", "-p", "rho_t=7850", "-p", "R=5e9", "-p", "Y=1.5e9",
         "--velocities", "1000,2000", "--json", js])
    d = json.load(open(js))
    for r in d["results"]:
        o = r["outputs"]
        if o["stop"] != "U = 0" or abs(o["P"] - o["P_erosion_exact"]) > 1e-9 * o["P_erosion_exact"]:
            sys.exit(f"FAIL: tate outputs {o}")

    # Issue 11 regressions. R = Y used to hang (a NaN quadrature tolerance); it must finish quickly
    # with the closed-form depth P = (L0 - L_f)/mu, mu = sqrt(rho_t/rho_p) (tests/unit/penetration).
    L0, rho_p, rho_t, V0, RY = 0.07354, 19235.0, 2300.0, 3300.0, 1e9
    mu = math.sqrt(rho_t / rho_p)
    Lf = L0 * math.exp(-mu * rho_p * V0 * V0 / (2 * (1 + mu) * RY))
    js = os.path.join(a.out, "tate_r_eq_y.json")
    try:
        subprocess.run([b, "models", "tate", "-p", f"L={L0}", "-p", f"rho_p={rho_p}", "-p", f"rho_t={rho_t}",
                        "-p", f"V={V0}", "-p", f"R={RY}", "-p", f"Y={RY}", "--json", js], check=True, timeout=20,
                       capture_output=True)
    except subprocess.TimeoutExpired:
        sys.exit("FAIL: tate with R = Y hangs")
    o = json.load(open(js))["results"][0]["outputs"]
    if abs(o["P_erosion_exact"] - (L0 - Lf) / mu) > 1e-9 * L0:
        sys.exit(f"FAIL: tate R = Y exact depth {o['P_erosion_exact']} m, closed form {(L0 - Lf) / mu} m")
    # A result that overflows is an error naming the result, not a '-nan' success.
    p = run([b, "models", "eichelberger", "-p", "L=0.07354", "-p", "rho_p=19235", "-p", "rho_t=2300",
             "-p", "V=1e308", "-p", "R=1e9", "-p", "Y=1e9"], expect_ok=False)
    if "not a finite number" not in p.stderr or "nan" in p.stdout.lower():
        sys.exit(f"FAIL: eichelberger V=1e308: stdout {p.stdout!r} stderr {p.stderr!r}")
    run([b, "models", "birkhoff", "-p", "L=inf", "-p", "rho_p=19235", "-p", "rho_t=2300"], expect_ok=False)

    # Bad input: the error names the offending option or parameter.
    for args, word in [(["tate", "-p", "rho_p=abc"], "rho_p"), (["tate", "-p", "L=0.1", "-p", "bogus=1"], "bogus"),
                       (["birkhoff", "-p", "L=0.1", "-p", "rho_p=-1", "-p", "rho_t=2300"], "rho_p"),
                       (["no-such-model"], "no-such-model")]:
        p = run([b, "models"] + args, expect_ok=False)
        if word not in p.stderr:
            sys.exit(f"FAIL: error for {args} does not name {word}: {p.stderr}")
    print("models CLI: OK")


if __name__ == "__main__":
    main()
