#pragma once
// Bracketed scalar root finding by the Illinois variant of regula falsi (Dowell & Jarratt, BIT 11
// (1971) 168-174): the false-position point, with the retained end's function value halved when
// the same end is kept twice, which restores superlinear convergence (order ~1.44) while the root
// stays bracketed. A false-position point outside the bracket, or an infinite end value, falls
// back to bisection.
#include <algorithm>
#include <cmath>

namespace ballista {

namespace illinois_detail {

/// Puts the new point (x, fx) in place of the bracket end of its sign; when the same end is
/// replaced twice running, the retained end's value is halved (the Illinois modification).
/// side: -1/+1 the end replaced last (a/b), 0 none yet.
inline void replace_end(double x, double fx, double& a, double& fa, double& b, double& fb, int& side) {
  if ((fx > 0.0) == (fa > 0.0)) {
    a = x;
    fa = fx;
    if (side == -1) fb *= 0.5;
    side = -1;
  } else {
    b = x;
    fb = fx;
    if (side == 1) fa *= 0.5;
    side = 1;
  }
}

}  // namespace illinois_detail

/// Root of f in the bracket [a, b] (either order) with fa = f(a) and fb = f(b) of opposite signs
/// (or one zero). Stops when |f(x)| <= ftol, when the bracket is narrower than xtol, or after
/// max_it evaluations. Returns the last point at which f was evaluated (b if none was), so that
/// a caller whose f records side results at each call can use those of the returned point.
template <class F>
double illinois_root(F&& f, double a, double fa, double b, double fb, double xtol, double ftol, int max_it = 100) {
  double x = b, fx = fb;
  int side = 0;
  for (int it = 0; it < max_it && std::abs(fx) > ftol && std::abs(b - a) > xtol; ++it) {
    const bool finite = std::isfinite(fa) && std::isfinite(fb) && fb != fa;
    x = finite ? (a * fb - b * fa) / (fb - fa) : 0.5 * (a + b);
    if (!(std::min(a, b) < x && x < std::max(a, b))) x = 0.5 * (a + b);
    fx = f(x);
    illinois_detail::replace_end(x, fx, a, fa, b, fb, side);
  }
  return x;
}

/// Root of f by the secant method through the two latest points, kept in the bracket [a, b]
/// (fa, fb of opposite signs, or one zero): the bracket is kept exactly as illinois_root keeps it
/// (the retained end's value halved when the same end is kept twice), and each step takes the
/// secant point if it lies inside the bracket and the last step at least halved |f|, the Illinois
/// point otherwise. The secant's order (1.618) beats Illinois' (~1.44) near a smooth root, and the
/// bracket keeps the guarantee. Stops as illinois_root, and also after a step shorter than xtol
/// (secant steps approach the root from one side, so the bracket need not shrink); same return
/// value.
template <class F>
double bracketed_secant_root(F&& f, double a, double fa, double b, double fb, double xtol, double ftol,
                             int max_it = 100) {
  double x = b, fx = fb, x_prev = a, f_prev = fa;
  int side = 0;
  bool moved = true;
  for (int it = 0; it < max_it && moved && std::abs(fx) > ftol && std::abs(b - a) > xtol; ++it) {
    const bool progress = std::abs(fx) <= 0.5 * std::abs(f_prev);
    double next = (progress && std::isfinite(fx) && std::isfinite(f_prev) && fx != f_prev)
                      ? x - fx * (x - x_prev) / (fx - f_prev)
                      : NAN;
    if (!(std::min(a, b) < next && next < std::max(a, b))) {
      const bool finite = std::isfinite(fa) && std::isfinite(fb) && fb != fa;
      next = finite ? (a * fb - b * fa) / (fb - fa) : 0.5 * (a + b);
      if (!(std::min(a, b) < next && next < std::max(a, b))) next = 0.5 * (a + b);
    }
    moved = std::abs(next - x) > xtol;
    x_prev = x;
    f_prev = fx;
    x = next;
    fx = f(x);
    illinois_detail::replace_end(x, fx, a, fa, b, fb, side);
  }
  return x;
}

}  // namespace ballista
