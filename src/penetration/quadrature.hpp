#pragma once
// Adaptive Simpson quadrature for smooth one-dimensional integrands (the Walters-Segletes
// integrals). Header-only, used by walters_segletes.cpp.
#include <cmath>

namespace ballista::penetration {

namespace detail {
template <class F>
double simpson_refine(const F& f, double a, double b, double fa, double fm, double fb, double whole, double tol,
                      int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
  const double delta = left + right - whole;
  // Richardson: the error of the refined sum is about delta / 15.
  if (depth <= 0 || std::abs(delta) <= 15 * tol) return left + right + delta / 15;
  return simpson_refine(f, a, m, fa, flm, fm, left, tol / 2, depth - 1) +
         simpson_refine(f, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}
}  // namespace detail

/// int_a^b f(x) dx to the absolute tolerance abs_tol (recursion depth at most 50).
template <class F>
double integrate_adaptive_simpson(const F& f, double a, double b, double abs_tol) {
  if (a == b) return 0;
  const double fa = f(a), fb = f(b), m = 0.5 * (a + b), fm = f(m);
  const double whole = (b - a) / 6 * (fa + 4 * fm + fb);
  return detail::simpson_refine(f, a, b, fa, fm, fb, whole, abs_tol, 50);
}

}  // namespace ballista::penetration
