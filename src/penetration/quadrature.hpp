#pragma once
// Adaptive Simpson quadrature for smooth one-dimensional integrands (the Walters-Segletes
// integrals). Header-only, used by walters_segletes.cpp.
//
// Guarded: a non-finite tolerance, interval or integrand value is an error (a NaN tolerance makes
// the accuracy test fail everywhere, and the recursion would then visit 2^50 intervals), and the
// number of integrand evaluations is capped.
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "core/error.hpp"

namespace ballista::penetration {

namespace detail {
template <class F>
struct CountedIntegrand {
  const F& f;
  long calls = 0;
  long budget;
  double operator()(double x) {
    if (++calls > budget)
      throw Error(fmt::format("adaptive Simpson quadrature: no convergence within {} integrand evaluations", budget));
    const double y = f(x);
    if (!std::isfinite(y))
      throw Error(fmt::format("adaptive Simpson quadrature: the integrand is {} at x = {:.17g}", y, x));
    return y;
  }
};

template <class G>
double simpson_refine(G& f, double a, double b, double fa, double fm, double fb, double whole, double tol, int depth) {
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

/// int_a^b f(x) dx to the absolute tolerance abs_tol (recursion depth at most 50, at most
/// max_evaluations integrand calls). Throws ballista::Error on a non-finite bound, tolerance or
/// integrand value, or when the budget is spent.
template <class F>
double integrate_adaptive_simpson(const F& f, double a, double b, double abs_tol, long max_evaluations = 4'000'000) {
  if (!std::isfinite(a) || !std::isfinite(b) || !(abs_tol >= 0) || !std::isfinite(abs_tol))
    throw Error(fmt::format("adaptive Simpson quadrature: bad interval [{}, {}] or tolerance {}", a, b, abs_tol));
  if (a == b) return 0;
  detail::CountedIntegrand<F> g{f, 0, max_evaluations};
  const double fa = g(a), fb = g(b), m = 0.5 * (a + b), fm = g(m);
  const double whole = (b - a) / 6 * (fa + 4 * fm + fb);
  return detail::simpson_refine(g, a, b, fa, fm, fb, whole, abs_tol, 50);
}

}  // namespace ballista::penetration
