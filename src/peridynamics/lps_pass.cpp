// The two passes of the linear peridynamic solid (model, sources and the dissipation at a break in
// lps_pass.hpp).
#include "peridynamics/lps_pass.hpp"

#include <algorithm>
#include <cmath>

namespace ballista::pd {

void lps_weighted_volume(const LpsPassArgs& a, Index p0, Index p1, double* m) {
  for (Index p = p0; p < p1; ++p) {
    double s = 0.0;
    for (Index k = a.offset[p]; k < a.offset[p + 1]; ++k)
      s += a.length0[k] * a.length0[k] * (a.beta[k] * a.vol0[a.other[k]]);
    m[p] = s;
  }
}

void lps_dilatation(const LpsPassArgs& a, Index p) {
  const double* x = a.x;
  const double xp0 = x[3 * p], xp1 = x[3 * p + 1], xp2 = x[3 * p + 2], s0p = a.s0[p];
  double sum_new = 0.0, sum_old = 0.0, m_new = 0.0, m_old = 0.0, vb = 0.0, smx = a.smax[p];
  bool breaks = false;
  for (Index k = a.offset[p]; k < a.offset[p + 1]; ++k) {
    const Index q = a.other[k];
    const double bv = a.beta[k] * a.vol0[q];
    if (a.broken[k]) {
      vb += bv;
      continue;
    }
    const double y0 = x[3 * q] - xp0, y1 = x[3 * q + 1] - xp1, y2 = x[3 * q + 2] - xp2;
    const double r = std::sqrt(y0 * y0 + y1 * y1 + y2 * y2), r0 = a.length0[k];
    const double s = r * a.inv_length0[k] - 1.0;
    const double term = r0 * (r - r0) * bv, mterm = r0 * r0 * bv;
    sum_old += term;
    m_old += mterm;
    if (s > std::min(s0p, a.s0[q])) {
      // Both ends decide alike from the same two positions and s0 values; this rank's copy at a
      // ghost end is set here (its owner sets its own).
      a.broken[k] = kBreaking;
      if (a.ghost[q]) a.broken[a.offset[q] + a.mirror[k]] = kBreaking;
      vb += bv;
      breaks = true;
      continue;
    }
    sum_new += term;
    m_new += mterm;
    if (a.alpha > 0.0) smx = std::max(smx, -a.alpha * s);
  }
  const double mp = a.m[p];
  const std::int64_t mat = a.material[p];
  // theta and B (lps_pass.hpp) of one state: S = theta (m - m_intact) / 3.
  auto state = [&](double sum, double m_intact, double& theta, double& coef) {
    if (!(mp > 0.0)) {
      theta = coef = 0.0;
      return;
    }
    theta = 3.0 * sum / mp;
    const double alpha = 15.0 * a.shear[mat] / mp, S = theta * (mp - m_intact) / 3.0;
    coef = 3.0 * a.bulk[mat] * theta / mp - alpha * (theta / 3.0 + S / mp);
  };
  state(sum_new, m_new, a.theta[p], a.coef[p]);
  state(sum_old, m_old, a.theta_old[p], a.coef_old[p]);
  a.breaks[p] = breaks ? 1.0 : 0.0;
  a.vol_broken[p] = vb;
  a.smax[p] = smx;
}

namespace {

/// Force and energy density of point p over its bonds in one state: `old` counts the bonds that
/// break in this evaluation as intact and takes theta_old. Returns W_p; adds the force to f.
double lps_point(const LpsPassArgs& a, Index p, bool old, double f[3]) {
  const double* x = a.x;
  const double* coef = old ? a.coef_old : a.coef;
  const double xp0 = x[3 * p], xp1 = x[3 * p + 1], xp2 = x[3 * p + 2], vp = a.vol0[p];
  const double mp = a.m[p];
  if (!(mp > 0.0)) return 0.0;
  const std::int64_t matp = a.material[p];
  const double thp = old ? a.theta_old[p] : a.theta[p];
  const double alpha_p = 15.0 * a.shear[matp] / mp, bp = coef[p];
  double fx = 0.0, fy = 0.0, fz = 0.0, wdev = 0.0;
  for (Index k = a.offset[p]; k < a.offset[p + 1]; ++k) {
    const std::uint8_t state = a.broken[k];
    if (state == 1 || (state == kBreaking && !old)) continue;
    const Index q = a.other[k];
    const double y0 = x[3 * q] - xp0, y1 = x[3 * q + 1] - xp1, y2 = x[3 * q + 2] - xp2;
    const double r = std::sqrt(y0 * y0 + y1 * y1 + y2 * y2), r0 = a.length0[k];
    const double e = r - r0, bv = a.beta[k] * a.vol0[q];
    const double alpha_q = 15.0 * a.shear[a.material[q]] / a.m[q];
    // t_pq + t_qp, each end's force state on the bond (lps_pass.hpp).
    const double t = (bp + coef[q]) * r0 + (alpha_p + alpha_q) * e;
    if (r > 0.0) {
      const double G = t * bv * vp / r;
      fx += G * y0, fy += G * y1, fz += G * y2;
    }
    const double ed = e - thp * r0 / 3.0;
    wdev += ed * ed * bv;
  }
  f[0] += fx, f[1] += fy, f[2] += fz;
  return 0.5 * a.bulk[matp] * thp * thp + 0.5 * alpha_p * wdev;
}

}  // namespace

void lps_forces(const LpsPassArgs& a, Index p) {
  const double* x = a.x;
  const double xp0 = x[3 * p], xp1 = x[3 * p + 1], xp2 = x[3 * p + 2], vp = a.vol0[p];
  double f[3] = {0.0, 0.0, 0.0};
  // The ends of broken bonds meet again through contact only (bond_pass.hpp's spring: force
  // c_s (d - r) V_p V_q apart, energy c_s V_p V_q (d - r)^2 / 2, half booked at each end).
  bool near_break = a.breaks[p] != 0.0;
  double ec = 0.0, kc = 0.0;
  for (Index k = a.offset[p]; k < a.offset[p + 1]; ++k) {
    const Index q = a.other[k];
    if (a.broken[k] != 1) {
      near_break = near_break || a.breaks[q] != 0.0;
      continue;
    }
    if (!a.contact) continue;
    const double y0 = x[3 * q] - xp0, y1 = x[3 * q + 1] - xp1, y2 = x[3 * q + 2] - xp2;
    const double r = std::sqrt(y0 * y0 + y1 * y1 + y2 * y2);
    const double d = std::min(0.9 * a.length0[k], a.range);
    if (!(r < d)) continue;
    const double cs = a.cs_over_c * a.micromodulus[a.material[p] * a.nmat + a.material[q]], o = d - r;
    const double vv = vp * a.vol0[q];
    kc += cs * a.vol0[q];
    ec += 0.25 * cs * o * o * vv;
    if (r > 0.0) {
      const double F = cs * o * vv / r;
      f[0] -= F * y0, f[1] -= F * y1, f[2] -= F * y2;
    }
  }
  double fb[3] = {0.0, 0.0, 0.0};
  const double w = lps_point(a, p, false, fb);
  a.f[3 * p] = fb[0] + f[0], a.f[3 * p + 1] = fb[1] + f[1], a.f[3 * p + 2] = fb[2] + f[2];
  a.energy[p] = w * vp;
  a.e_contact[p] = ec;
  a.k_contact[p] = kc;
  a.dissipated[p] = 0.0;
  if (near_break) {
    // The state before this evaluation's failures, at the same positions (lps_pass.hpp).
    double g[3] = {0.0, 0.0, 0.0};
    const double w_old = lps_point(a, p, true, g);
    double df = 0.0;
    const double* xp = a.x_prev;
    for (int c = 0; c < 3; ++c) df += (g[c] - fb[c]) * (x[3 * p + c] - xp[3 * p + c]);
    a.dissipated[p] = (w_old - w) * vp + 0.5 * df;
  }
}

}  // namespace ballista::pd
