// The passes of the linear peridynamic solid (model, sources, the plasticity and the
// dissipation at a break in lps_pass.hpp).
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

void lps_deviatoric_stiffness(const LpsPassArgs& a, Index p0, Index p1, double* alpha) {
  for (Index p = p0; p < p1; ++p) alpha[p] = a.m[p] > 0.0 ? 15.0 * a.shear[a.material[p]] / a.m[p] : 0.0;
}

void lps_coefficients(const LpsPassArgs& a, Index p, double plastic_sum, double plastic_sum_old) {
  const double mp = a.m[p];
  if (!(mp > 0.0)) {
    a.coef[p] = a.coef_old[p] = 0.0;
    return;
  }
  const double alpha = a.alpha_point[p], K = a.bulk[a.material[p]];
  auto coefficient = [&](double theta, double S) { return 3.0 * K * theta / mp - alpha * (theta / 3.0 + S / mp); };
  a.coef[p] = coefficient(a.theta[p], a.s_elastic[p] - plastic_sum);
  a.coef_old[p] = a.breaks[p] != 0.0 ? coefficient(a.theta_old[p], a.s_elastic_old[p] - plastic_sum_old) : a.coef[p];
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
    if (a.length) a.length[k] = r;
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
  // theta, and S without plastic extensions, sum (e - theta |xi| / 3) |xi| beta V =
  // sum - theta m_intact / 3, of both states; lps_return takes the plastic part off.
  a.theta[p] = mp > 0.0 ? 3.0 * sum_new / mp : 0.0;
  a.theta_old[p] = mp > 0.0 ? 3.0 * sum_old / mp : 0.0;
  a.s_elastic[p] = sum_new - a.theta[p] * m_new / 3.0;
  a.s_elastic_old[p] = sum_old - a.theta_old[p] * m_old / 3.0;
  a.breaks[p] = breaks ? 1.0 : 0.0;
  lps_coefficients(a, p, 0.0, 0.0);
  a.vol_broken[p] = vb;
  a.smax[p] = smx;
}

void lps_return(const LpsPassArgs& a, Index p) {
  const double mp = a.m[p];
  if (!(mp > 0.0)) return;
  const double alpha = a.alpha_point[p];
  const Index k0 = a.offset[p], k1 = a.offset[p + 1];
  double* ep = a.plastic;
  // Radial return of the point's deviatoric force state (lps_pass.hpp) in the state before this
  // evaluation's failures (theta_old, the breaking bonds still in): the constitutive update
  // first, then the breaks, which change the stored energy at fixed e^p (lps_forces books it).
  const double th = a.theta_old[p];
  double norm2 = 0.0;
  for (Index k = k0; k < k1; ++k) {
    if (a.broken[k] == 1) continue;
    const double r0 = a.length0[k], ed = a.length[k] - r0 - th * r0 / 3.0;
    const double td = alpha * (ed - ep[k]);
    norm2 += td * td * (a.beta[k] * a.vol0[a.other[k]]);
  }
  const double two_psi0 = 5.0 * a.yield_sq / mp;
  double* td_prev = a.td_prev;
  if (norm2 > two_psi0) {
    const double scale = std::sqrt(two_psi0 / norm2);
    const double dlambda = (1.0 / scale - 1.0) / alpha;
    // The plastic work of the step by the trapezoidal rule, (t^d_n + t^d_n+1) . de^p / 2 with
    // de^p = dlambda t^d_n+1 (lps_pass.hpp).
    double cross = 0.0;
    for (Index k = k0; k < k1; ++k) {
      if (a.broken[k] == 1) continue;
      const double r0 = a.length0[k], ed = a.length[k] - r0 - th * r0 / 3.0;
      const double td = scale * alpha * (ed - ep[k]);
      cross += td_prev[k] * td * (a.beta[k] * a.vol0[a.other[k]]);
      ep[k] += dlambda * td;
    }
    a.dissipated[p] = 0.5 * dlambda * (cross + two_psi0) * a.vol0[p];
  }
  // The plastic part of S in both states, and the deviatoric force state after this evaluation's
  // failures (the next step's t^d_n).
  const double th_new = a.theta[p];
  double sum = 0.0, sum_old = 0.0;
  for (Index k = k0; k < k1; ++k) {
    const std::uint8_t state = a.broken[k];
    if (state == 1) continue;
    const double r0 = a.length0[k], term = ep[k] * r0 * (a.beta[k] * a.vol0[a.other[k]]);
    sum_old += term;
    if (state == kBreaking) continue;
    sum += term;
    td_prev[k] = alpha * (a.length[k] - r0 - th_new * r0 / 3.0 - ep[k]);
  }
  lps_coefficients(a, p, sum, sum_old);
}

namespace {

/// Contact of broken bonds and whether a neighbour breaks, gathered by the new state's loop.
struct NewStateExtras {
  double f[3] = {0.0, 0.0, 0.0};  ///< contact force, N
  double ec = 0.0, kc = 0.0;      ///< contact energy (this end's half), J; stiffness, N/m^4
  bool near_break = false;        ///< a bond of p, or of a neighbour, breaks in this evaluation
};

/// Force and stored energy density of point p over its bonds in one state: `old` counts the
/// bonds that break in this evaluation as intact and takes theta_old and coef_old. Returns W_p;
/// adds the bonds' force to f. The new state's loop (extras given) also takes the contact of the
/// ends of broken bonds (bond_pass.hpp's spring: force c_s (d - r) V_p V_q apart, energy
/// c_s V_p V_q (d - r)^2 / 2, half booked at each end) and looks for breaks at the neighbours.
double lps_point(const LpsPassArgs& a, Index p, bool old, double f[3], NewStateExtras* extras) {
  const double* x = a.x;
  const double* coef = old ? a.coef_old : a.coef;
  const double* ep = a.plastic;
  const double* alpha = a.alpha_point;
  const double xp0 = x[3 * p], xp1 = x[3 * p + 1], xp2 = x[3 * p + 2], vp = a.vol0[p];
  if (!(a.m[p] > 0.0)) return 0.0;
  const std::int64_t matp = a.material[p];
  const double thp = old ? a.theta_old[p] : a.theta[p];
  const double alpha_p = alpha[p], bp = coef[p];
  const bool look_for_breaks = extras && a.any_break;
  double fx = 0.0, fy = 0.0, fz = 0.0, wdev = 0.0;
  for (Index k = a.offset[p]; k < a.offset[p + 1]; ++k) {
    const std::uint8_t state = a.broken[k];
    if (state == kBreaking && !old) continue;
    const Index q = a.other[k];
    if (state == 1) {
      if (!extras || !a.contact) continue;
      const double y0 = x[3 * q] - xp0, y1 = x[3 * q + 1] - xp1, y2 = x[3 * q + 2] - xp2;
      const double r = std::sqrt(y0 * y0 + y1 * y1 + y2 * y2);
      const double d = std::min(0.9 * a.length0[k], a.range);
      if (!(r < d)) continue;
      const double cs = a.cs_over_c * a.micromodulus[matp * a.nmat + a.material[q]], o = d - r;
      const double vv = vp * a.vol0[q];
      extras->kc += cs * a.vol0[q];
      extras->ec += 0.25 * cs * o * o * vv;
      if (r > 0.0) {
        const double F = cs * o * vv / r;
        extras->f[0] -= F * y0, extras->f[1] -= F * y1, extras->f[2] -= F * y2;
      }
      continue;
    }
    if (look_for_breaks) extras->near_break = extras->near_break || a.breaks[q] != 0.0;
    const double y0 = x[3 * q] - xp0, y1 = x[3 * q + 1] - xp1, y2 = x[3 * q + 2] - xp2;
    const double r = std::sqrt(y0 * y0 + y1 * y1 + y2 * y2), r0 = a.length0[k];
    const double e = r - r0, bv = a.beta[k] * a.vol0[q];
    const double ep_p = ep ? ep[k] : 0.0, ep_q = ep ? ep[a.offset[q] + a.mirror[k]] : 0.0;
    // t_pq + t_qp, each end's force state on the bond (lps_pass.hpp).
    const double t = (bp + coef[q]) * r0 + alpha_p * (e - ep_p) + alpha[q] * (e - ep_q);
    if (r > 0.0) {
      const double G = t * bv * vp / r;
      fx += G * y0, fy += G * y1, fz += G * y2;
    }
    const double ed = e - thp * r0 / 3.0 - ep_p;
    wdev += ed * ed * bv;
  }
  f[0] += fx, f[1] += fy, f[2] += fz;
  return 0.5 * a.bulk[matp] * thp * thp + 0.5 * alpha_p * wdev;
}

}  // namespace

void lps_forces(const LpsPassArgs& a, Index p) {
  const double* x = a.x;
  const double vp = a.vol0[p];
  NewStateExtras extras;
  extras.near_break = a.breaks[p] != 0.0;
  double fb[3] = {0.0, 0.0, 0.0};
  const double w = lps_point(a, p, false, fb, &extras);
  for (int c = 0; c < 3; ++c) a.f[3 * p + c] = fb[c] + extras.f[c];
  a.energy[p] = w * vp;
  a.e_contact[p] = extras.ec;
  a.k_contact[p] = extras.kc;
  if (extras.near_break) {
    // The state before this evaluation's failures, at the same positions (lps_pass.hpp).
    double g[3] = {0.0, 0.0, 0.0};
    const double w_old = lps_point(a, p, true, g, nullptr);
    double df = 0.0;
    const double* xp = a.x_prev;
    for (int c = 0; c < 3; ++c) df += (g[c] - fb[c]) * (x[3 * p + c] - xp[3 * p + c]);
    a.dissipated[p] += (w_old - w) * vp + 0.5 * df;
  }
}

}  // namespace ballista::pd
