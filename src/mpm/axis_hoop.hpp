#pragma once
// The hoop operator of axisymmetric uGIMP next to the symmetry axis.
//
// Axisymmetric MPM adds the hoop strain rate and its force (thesis seed 000 ch. 5):
//   L_tt = sum_I T_I v_r,I,    f_r,I -= V_p sigma_tt T_I,
// and away from the axis T_I = S_I(x_p) / r_p. A uGIMP particle whose domain [r_p - l, r_p + l]
// reaches across the axis (r_p < l) breaks that form: the weight of the first node off the axis
// does not vanish with r_p (it tends to l / 4h), so S_I / r_p and with it the hoop rate grow
// without bound as a particle drifts onto the axis, and the rate-form F_tt goes negative.
// Nairn & Guilkey (IJNME 101 (2015) 127, the axisymmetric GIMP) average over the particle domain
// with the axisymmetric measure r dr dz; the hoop term is the domain average of N_I / r:
//   T_I = integral_D N_I dA / integral_D r dA,
// with D the part of the domain on the material side of the axis, r in [0, r_p + l]. For a
// domain inside r >= 0 this is S_I / r_p exactly (integral of r over [r_p - l, r_p + l] is 2 l r_p),
// so only the particles whose domain crosses the axis change. The operator is bounded (the
// denominator is at least l^2 / 2 per unit axial length), reproduces the uniform expansion
// v_r = a r exactly (sum_I r_I N_I = r on r >= 0), and the force and the rate share it, so the
// internal power sum_I f_I . v_I = -V_p sigma : L still holds and the USAVG energy audit closes.
//
// Per stencil entry k with radial node i: T_k = w_k * rho_i * 4 l / b^2, b = r_p + l, where
// rho_i = integral_0^b N_i dr / integral_(r_p - l)^b N_i dr is the share of the node's radial
// weight on the material side (w_k carries the axial factor).
#include <algorithm>

#include "mpm/graded_shape_functions.hpp"
#include "mpm/grid_geometry.hpp"

namespace ballista {

namespace axis_hoop_detail {

/// Radial node coordinate of block index i.
inline double radial_node(const GridGeometry& g, int i) {
  return g.graded ? (*g.graded)[0].at(i) : g.origin[0] + i * g.h;
}

/// The half-length the uGIMP stencils use on the radial axis (the same clamps as gimp_stencil
/// and graded_detail::gimp_1d).
inline double effective_half_length(const GridGeometry& g, double r, double lp) {
  if (!g.graded) return std::min(std::max(lp / g.h, 1e-12), 0.5) * g.h;
  const GradedAxis& ax = (*g.graded)[0];
  const int c = ax.cell_of(r);
  const double hmin = std::min({ax.cell_size(c - 1), ax.cell_size(c), ax.cell_size(c + 1)});
  return std::min(std::max(lp, 1e-12 * hmin), 0.5 * hmin);
}

}  // namespace axis_hoop_detail

/// For a uGIMP particle at radius r with radial half-length lp in a 2D axisymmetric grid whose
/// axis is at r = 0: if its domain crosses the axis, writes the hoop operator T_k of each entry
/// of `st` into `hoop` and returns true; otherwise returns false and the caller uses w_k / r.
/// Out of line: it runs for the few particles next to the axis, and the hot transfer loops that
/// call it stay as they were compiled.
[[gnu::noinline]] inline bool axis_hoop_weights(const GridGeometry& g, double r, double lp, const Stencil<2>& st,
                                                double* hoop) {
  using namespace axis_hoop_detail;
  using graded_detail::hat_integral;
  const double l = effective_half_length(g, r, lp);
  if (!(r < l)) return false;
  const double lo = r - l, hi = r + l;
  const double scale = 4.0 * l / (hi * hi);
  const Index row = g.nodes[0];
  for (int k = 0; k < st.count; ++k) {
    const int i = static_cast<int>(st.node[k] % row);
    const double xl = radial_node(g, i - 1), xi = radial_node(g, i), xr = radial_node(g, i + 1);
    const double whole = hat_integral(xl, xi, xr, lo, hi);
    const double inside = hat_integral(xl, xi, xr, std::max(lo, 0.0), hi);
    hoop[k] = whole > 0.0 ? st.w[k] * (inside / whole) * scale : 0.0;
  }
  return true;
}

/// The hoop rate L_tt = sum_k T_k v_r of the same particle from the grid velocities `field` (the
/// node velocities of its velocity field); false where axis_hoop_weights is.
[[gnu::noinline]] inline bool axis_hoop_rate(const GridGeometry& g, double r, double lp, const Stencil<2>& st,
                                             const Vec3* field, double& rate) {
  double hoop[Stencil<2>::kMax];
  if (!axis_hoop_weights(g, r, lp, st, hoop)) return false;
  rate = 0.0;
  for (int k = 0; k < st.count; ++k) rate += hoop[k] * field[st.node[k]][0];
  return true;
}

}  // namespace ballista
