#!/usr/bin/python3
"""validation/shaped_charge_theory.py's collapse angles against what they stand for.

- PER's collapse angle against the liner's profile built element by element: elements of a 30°
  cone (half-angle) at x = 5-25 mm from the apex, lit by a point detonation behind the apex (so the
  sweep speed U changes along the liner), each flying straight at its own V0(x) = 900 + 6e4 x m/s
  along the normal deflected by Taylor's delta = asin(V0 / 2U). At the instant an element reaches
  the axis, its two neighbours at x +- 1e-6 m are placed where they are then, and the angle of the
  chord between them against the axis is the collapse angle. The formula is the limit of that
  chord; the two differ by a few 1e-9 rad, set by the central differences (step 1e-5 m) that give
  the formula its delta' and T' (the chord's own O(h^2) is about 1e-11 rad). A sign error in any
  one term moves beta by more than 0.02 rad, so the bound 1e-6 rad fails it.
- The steady limit (V0 and delta constant along the liner, the sweep along a cone lit by a plane
  wave): beta = alpha + 2 delta to round-off (BMPT 1948).
- The accelerating element (V = V0 (1 - exp(-(t - t0)/tau)), with V0, t0 and tau changing along
  the liner) against the same construction, the neighbours flown along their own histories; and
  its tau -> 0 limit (tau = 1e-12 s, tau' = 0) against PER's angle with T = t0 (to 1e-9 rad: the
  limit's own error is tau-sized).
- The jet relations at an unsteady beta (BMPT's steady beta and two others): V1 +- V2 in the
  collision point's frame, where the wall flows in along its own direction.
- fit_acceleration on a history written from known V0, t0 and tau (frames every 0.25 us, as the
  runs write them, up to the largest speed): recovered to 1e-6 relative (least squares on exact
  data).
- With U constant the formula is PER's as Walters & Zukas write it (ch. 2):
  tan beta = [sin a + 2 sin d cos(a + d) - x sin a (1 - tan(a + d) tan d) V0'/V0]
           / [cos a - 2 sin d sin(a + d) + x sin a (tan(a + d) + tan d) V0'/V0], to round-off."""
import math
import sys

import script_args


def bisect_root(f, a, b):
    """Root of f in [a, b] by bisection to round-off (f changes sign once there)."""
    fa = f(a)
    for _ in range(200):
        m = 0.5 * (a + b)
        fm = f(m)
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
        if b - a <= 1e-16 * abs(b):
            break
    return 0.5 * (a + b)


def main():
    script_args.parse()
    from shaped_charge_theory import accelerated_collapse, fit_acceleration, jet_from_collapse, per_collapse_angle
    failures = 0
    alpha, D, det_behind = math.radians(30.0), 7980.0, 0.012  # detonator on the axis 12 mm behind the apex

    def v0(x):
        return 900.0 + 6.0e4 * x

    def arrival(x):  # program burn from the point: straight-line distance over D
        return math.hypot(x * math.tan(alpha), x + det_behind) / D

    def sweep(x, h=1e-7):  # U = ds/dT along the generator, s = x / cos(alpha)
        return (2 * h / math.cos(alpha)) / (arrival(x + h) - arrival(x - h))

    def delta(x):
        return math.asin(v0(x) / (2.0 * sweep(x)))

    def position(x, t):
        th = alpha + delta(x)
        tau = t - arrival(x)
        return x + v0(x) * tau * math.sin(th), x * math.tan(alpha) - v0(x) * tau * math.cos(th)

    worst = 0.0
    for x in (5e-3, 10e-3, 15e-3, 20e-3, 25e-3):
        th = alpha + delta(x)
        t_c = arrival(x) + x * math.tan(alpha) / (v0(x) * math.cos(th))
        h = 1e-6
        (z1, r1), (z2, r2) = position(x - h, t_c), position(x + h, t_c)
        beta_built = math.atan2(r2 - r1, z2 - z1)
        e = 1e-5
        d_delta = (delta(x + e) - delta(x - e)) / (2 * e)
        d_T = (arrival(x + e) - arrival(x - e)) / (2 * e)
        beta = per_collapse_angle(alpha, x * math.tan(alpha), v0(x), 6.0e4, delta(x), d_delta, d_T)
        worst = max(worst, abs(beta - beta_built))
        print(f"x = {x * 1e3:4.1f} mm: PER beta {math.degrees(beta):8.4f} deg, built {math.degrees(beta_built):8.4f} deg,"
              f" steady {math.degrees(alpha + 2 * delta(x)):8.4f} deg")
    ok = worst < 1e-6
    print(f"PER against the built profile: largest difference {worst:.2e} rad (bound 1e-6): {'ok' if ok else 'FAIL'}")
    failures += not ok

    def tau(x):  # the acceleration's time constant grows along the liner
        return 0.3e-6 + 30e-6 * x

    def flown(x, t):
        th = alpha + delta(x)
        u = max(t - arrival(x), 0.0)
        s = v0(x) * (u - tau(x) * -math.expm1(-u / tau(x)))
        return x + s * math.sin(th), x * math.tan(alpha) - s * math.cos(th)

    worst = worst_speed = 0.0
    for x in (5e-3, 10e-3, 15e-3, 20e-3, 25e-3):
        t_c = bisect_root(lambda t: flown(x, t)[1], arrival(x), arrival(x) + 1e-4)
        h = 1e-6
        (z1, r1), (z2, r2) = flown(x - h, t_c), flown(x + h, t_c)
        built = math.atan2(r2 - r1, z2 - z1)
        e = 1e-5
        d = lambda f: (f(x + e) - f(x - e)) / (2 * e)
        beta, v_arr = accelerated_collapse(alpha, x * math.tan(alpha), v0(x), 6.0e4, delta(x), d(delta),
                                           arrival(x), d(arrival), tau(x), 30e-6)
        worst = max(worst, abs(beta - built))
        u = t_c - arrival(x)
        worst_speed = max(worst_speed, abs(v_arr - v0(x) * -math.expm1(-u / tau(x))) / v0(x))
    ok = worst < 1e-6 and worst_speed < 1e-9
    print(f"accelerating elements against the built profile: largest difference {worst:.2e} rad (bound 1e-6), "
          f"arrival speed {worst_speed:.1e} of V0 (bound 1e-9): {'ok' if ok else 'FAIL'}")
    failures += not ok
    x = 15e-3
    e = 1e-5
    d = lambda f: (f(x + e) - f(x - e)) / (2 * e)
    fast, _ = accelerated_collapse(alpha, x * math.tan(alpha), v0(x), 6.0e4, delta(x), d(delta), arrival(x),
                                   d(arrival), 1e-12, 0.0)
    per = per_collapse_angle(alpha, x * math.tan(alpha), v0(x), 6.0e4, delta(x), d(delta), d(arrival))
    ok = abs(fast - per) < 1e-9
    print(f"tau -> 0: {math.degrees(fast):.6f} deg against PER's {math.degrees(per):.6f} deg: {'ok' if ok else 'FAIL'}")
    failures += not ok

    worst = 0.0
    for a_deg, d_deg, U in ((20.0, 5.0, 9000.0), (30.0, 8.0, 8500.0), (45.0, 12.0, 12000.0)):
        a, d = math.radians(a_deg), math.radians(d_deg)
        V = 2 * U * math.sin(d)
        beta = per_collapse_angle(a, 0.01 * math.tan(a), V, 0.0, d, 0.0, 1.0 / (U * math.cos(a)))
        worst = max(worst, abs(beta - (a + 2 * d)))
    ok = worst < 1e-14
    print(f"steady limit beta = alpha + 2 delta: largest difference {worst:.1e} rad: {'ok' if ok else 'FAIL'}")
    failures += not ok

    worst = 0.0
    for a_deg, d_deg, U, x, dv in ((20.0, 5.0, 9000.0, 0.01, 5e4), (30.0, 8.0, 8500.0, 0.02, -3e4)):
        a, d = math.radians(a_deg), math.radians(d_deg)
        V = 2 * U * math.sin(d)
        ddelta = dv / (2 * U * math.cos(d))  # U constant: delta' = V0' / (2 U cos delta)
        beta = per_collapse_angle(a, x * math.tan(a), V, dv, d, ddelta, 1.0 / (U * math.cos(a)))
        g = x * math.sin(a) * dv / V
        per = math.atan2(math.sin(a) + 2 * math.sin(d) * math.cos(a + d) - g * (1 - math.tan(a + d) * math.tan(d)),
                         math.cos(a) - 2 * math.sin(d) * math.sin(a + d) + g * (math.tan(a + d) + math.tan(d)))
        worst = max(worst, abs(beta - per))
    ok = worst < 1e-14
    print(f"U constant: PER's formula as published: largest difference {worst:.1e} rad: {'ok' if ok else 'FAIL'}")
    failures += not ok

    # The jet relations in the collision point's frame (BMPT 1948; Walters & Zukas ch. 2): the point
    # moves along the axis at V1 = V0 cos(beta - alpha - delta) / sin(beta), the liner flows into it
    # at V2 = V0 cos(alpha + delta) / sin(beta); the jet leaves at V1 + V2, the slug at V1 - V2.
    a, d = math.radians(30.0), math.radians(7.0)
    for b in (a + 2 * d, math.radians(25.0), math.radians(70.0)):
        vj, vs, share = jet_from_collapse(1500.0, a, d, b)
        v1 = 1500.0 * math.cos(b - a - d) / math.sin(b)
        v2 = 1500.0 * math.cos(a + d) / math.sin(b)
        ok = abs(vj - (v1 + v2)) < 1e-9 * vj and abs(vs - (v1 - v2)) < 1e-9 * vj and abs(share - math.sin(b / 2) ** 2) < 1e-15
        print(f"beta {math.degrees(b):4.1f} deg: jet {vj:.3f} = V1 + V2 {v1 + v2:.3f}, slug {vs:.3f} = V1 - V2 "
              f"{v1 - v2:.3f}: {'ok' if ok else 'FAIL'}")
        failures += not ok

    V0, t0, tau0 = 1850.0, 3.1e-6, 1.05e-6
    times = [0.25e-6 * k for k in range(41)]  # 0 to 10 us
    speeds = [V0 * -math.expm1(-(t - t0) / tau0) if t > t0 else 0.0 for t in times]
    v_fit, t0_fit, tau_fit, rms = fit_acceleration(times, speeds)
    err = max(abs(v_fit - V0) / V0, abs(t0_fit - t0) / t0, abs(tau_fit - tau0) / tau0)
    ok = err < 1e-6
    print(f"fit of a known history: V0 {v_fit:.3f}, t0 {t0_fit * 1e6:.6f} us, tau {tau_fit * 1e6:.6f} us,"
          f" largest relative error {err:.1e} (bound 1e-6): {'ok' if ok else 'FAIL'}")
    failures += not ok
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
