#pragma once
// MPM shape functions on a graded grid (mpm/graded_axis.hpp): the linear hat, uGIMP and CPDI1
// with each axis's own node coordinates. The linear hat of node I is 1 at x_I and 0 at its
// neighbours x_(I-1), x_(I+1), linear in between (slopes 1/h_L and -1/h_R of the two cells it
// spans); uGIMP averages it over the particle domain and CPDI interpolates it between the domain
// corners, exactly as on a uniform grid (structured mesh refinement in GIMP: Ma, Lu & Komanduri,
// CMES 12 (2006) 213). On equal cells the weights are those of mpm/shape_functions.hpp to
// round-off (tests/unit/mpm/test_graded_shape_functions.cpp). The cubic B-spline on non-uniform
// knots is not here: a graded grid with shape_function bspline3 is refused.
#include <algorithm>
#include <cmath>

#include "mpm/grid_geometry.hpp"
#include "mpm/shape_functions.hpp"

namespace ballista {

namespace graded_detail {

/// Linear hat on one axis: nodes c, c+1 with N = 1 - t, t and dN/dx = -1/h_c, +1/h_c.
inline void linear_1d(const GradedAxis& ax, double x, shape_detail::Axis1D<2>& a) {
  double t;
  ax.locate(x, a.first, t);
  const double inv_h = ax.inv_cell[std::clamp(a.first, 0, ax.cells() - 1)];
  a.w[0] = 1.0 - t;
  a.w[1] = t;
  a.dw[0] = -inv_h;
  a.dw[1] = inv_h;
}

/// Node I's hat at y.
inline double hat(const GradedAxis& ax, int I, double y) {
  const double xl = ax.at(I - 1), xi = ax.at(I), xr = ax.at(I + 1);
  if (y <= xl || y >= xr) return 0.0;
  return y <= xi ? (y - xl) / (xi - xl) : (xr - y) / (xr - xi);
}

/// Integral over [lo, hi] of the hat that is 0 at xl, 1 at xi and 0 at xr, piece by piece (the
/// trapezoid rule is exact on each linear piece). Not as a difference of antiderivatives: a domain
/// that overlaps a node's support by a sliver r would lose its weight O(r^2) to cancellation while
/// its gradient O(r) survives, and a node with a gradient but no mass takes an unbounded
/// acceleration.
inline double hat_integral(double xl, double xi, double xr, double lo, double hi) {
  const double xs[3] = {xl, xi, xr};
  double sum = 0.0;
  for (int piece = 0; piece < 2; ++piece) {
    const double a = std::max(lo, xs[piece]), b = std::min(hi, xs[piece + 1]);
    if (!(b > a)) continue;
    const double inv = 1.0 / (xs[piece + 1] - xs[piece]);
    // The hat rises from 0 at xs[0] to 1 at xs[1], then falls to 0 at xs[2].
    const double na = piece == 0 ? (a - xs[0]) * inv : (xs[2] - a) * inv;
    const double nb = piece == 0 ? (b - xs[0]) * inv : (xs[2] - b) * inv;
    sum += 0.5 * (b - a) * (na + nb);
  }
  return sum;
}

/// Integral of node I's hat over [lo, hi].
inline double hat_integral(const GradedAxis& ax, int I, double lo, double hi) {
  return hat_integral(ax.at(I - 1), ax.at(I), ax.at(I + 1), lo, hi);
}

/// uGIMP on one axis (Bardenhagen & Kober, CMES 5 (2004) 477): S_I = (1/2lp) integral of the hat
/// over [x - lp, x + lp], dS_I/dx = (N_I(x + lp) - N_I(x - lp)) / 2lp. lp is clamped to half the
/// smallest of the particle's cell and its two neighbours, so the domain reaches at most one
/// neighbouring cell and three nodes cover it (a particle from coarse cells entering fine ones
/// keeps a domain its new cells can hold).
inline void gimp_1d(const GradedAxis& ax, double x, double lp, shape_detail::Axis1D<3>& a) {
  int c;
  double t;
  ax.locate(x, c, t);
  const double hmin = std::min({ax.cell_size(c - 1), ax.cell_size(c), ax.cell_size(c + 1)});
  const double l = std::min(std::max(lp, 1e-12 * hmin), 0.5 * hmin);
  a.first = x - l < ax.at(c) ? c - 1 : c;
  const double inv_2l = 0.5 / l;
  for (int n = 0; n < 3; ++n) {
    const int I = a.first + n;
    a.w[n] = hat_integral(ax, I, x - l, x + l) * inv_2l;
    a.dw[n] = (hat(ax, I, x + l) - hat(ax, I, x - l)) * inv_2l;
  }
}

}  // namespace graded_detail

template <int Dim>
[[gnu::always_inline]] inline void graded_linear_stencil(const GridGeometry& g, const Vec3& x, Stencil<Dim>& s) {
  shape_detail::Axis1D<2> ax[Dim];
  for (int d = 0; d < Dim; ++d) graded_detail::linear_1d((*g.graded)[d], x[d], ax[d]);
  s.count = 0;
  shape_detail::tensor_product<Dim, 2>(g, ax, s);
}

/// The trimmed uGIMP windows on a graded grid (GimpWindows).
template <int Dim>
[[gnu::always_inline]] inline void graded_gimp_windows(const GridGeometry& g, const Vec3& x, const Vec3& lp,
                                                       GimpWindows<Dim>& w) {
  for (int d = 0; d < Dim; ++d) {
    graded_detail::gimp_1d((*g.graded)[d], x[d], lp[d], w.ax[d]);
    w.n.n[d] = shape_detail::trim_gimp_window(w.ax[d]);
  }
}

template <int Dim>
inline void graded_gimp_stencil(const GridGeometry& g, const Vec3& x, const Vec3& lp, Stencil<Dim>& s) {
  GimpWindows<Dim> w;
  graded_gimp_windows<Dim>(g, x, lp, w);
  stencil_from_windows<Dim>(g, w, s);
}

/// CPDI1 (Sadeghirad, Brannon & Burghardt, IJNME 86 (2011) 1435; cpdi_stencil) with the graded
/// linear hats at the corners.
template <int Dim>
inline void graded_cpdi_stencil(const GridGeometry& g, const Vec3& x, const Mat3& r, Stencil<Dim>& s) {
  cpdi_stencil_located<Dim>(g, x, r, s,
                            [&](int d, double xc, int& c, double& t) { (*g.graded)[d].locate(xc, c, t); });
}

}  // namespace ballista
