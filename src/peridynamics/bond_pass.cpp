#include "peridynamics/bond_pass.hpp"

#include <algorithm>
#include <cmath>

namespace ballista::pd {

namespace {

/// The loop, compiled once per combination of the optional models so that the common case (elastic
/// bonds, no surface correction) carries no test for them per bond.
template <bool Plastic, bool Surface>
void bond_pass_t(const BondPassArgs& a, Index p0, Index p1) {
  const double* __restrict x = a.x;
  const double* __restrict vol0 = a.vol0;
  const std::int64_t* __restrict mat = a.material;
  const double* __restrict cmat = a.micromodulus;
  const int nmat = a.nmat;
  const double* __restrict s0 = a.s0;
  const double* __restrict len0 = a.length0;
  const double* __restrict inv_len0 = a.inv_length0;
  const float* __restrict beta = a.beta;
  const std::int32_t* __restrict other = a.other;
  const std::int32_t* __restrict mirror = a.mirror;
  std::uint8_t* __restrict broken = a.broken;
  const Index* __restrict offset = a.offset;
  const Index* __restrict upper = a.upper;
  double* __restrict sp = a.plastic_stretch;
  const double sy = a.yield_stretch, alpha = a.alpha, cs_over_c = a.cs_over_c, range = a.range;
  const bool contact = a.contact, bonded_contact = a.bonded_contact, lammps_break = a.lammps_break;
  const double* __restrict xprev = a.x_prev;
  double* __restrict f = a.f;
  double* __restrict energy = a.energy;
  double* __restrict dis = a.dissipated;
  double* __restrict vb = a.vol_broken;
  double* __restrict smax = a.smax;
  double* __restrict ec = a.e_contact;
  double* __restrict kc = a.k_contact;
  const double* __restrict lambda = a.surface_factor;

  for (Index p = p0; p < p1; ++p) {
    const double xp0 = x[3 * p], xp1 = x[3 * p + 1], xp2 = x[3 * p + 2], vp = vol0[p], s0p = s0[p];
    const double* crow = cmat + mat[p] * nmat;
    // Sums of p's own terms in registers; q's are added in memory.
    double fx = 0.0, fy = 0.0, fz = 0.0, ep = 0.0, smp = smax[p];
    for (Index k = upper[p]; k < offset[p + 1]; ++k) {
      const Index q = other[k];
      const double y0 = x[3 * q] - xp0, y1 = x[3 * q + 1] - xp1, y2 = x[3 * q + 2] - xp2;
      const double r = std::sqrt(y0 * y0 + y1 * y1 + y2 * y2), r0 = len0[k];
      const double vq = vol0[q], vv = vp * vq, bk = beta[k];
      const double c_bond = nmat == 1 ? crow[0] : crow[mat[q]];  // one material: no lookup
      // The bond's micromodulus, with the surface correction's mean factor of its ends if on;
      // contact springs keep the plain c.
      double cpq = c_bond;
      if constexpr (Surface) cpq *= 0.5 * (lambda[p] + lambda[q]);
      // A repulsive contact spring between p and q at r < d (Silling & Askari 2005; LAMMPS PERI):
      // force c_s (d - r) V_p V_q apart; energy c_s V_p V_q (d - r)^2 / 2, half at each end.
      auto repel = [&](double d) {
        const double cs = cs_over_c * c_bond, o = d - r;
        const double e = 0.25 * cs * o * o * vv;
        kc[p] += cs * vq;
        kc[q] += cs * vp;
        if (r > 0.0) {
          const double F = cs * o * vv / r;
          fx -= F * y0, fy -= F * y1, fz -= F * y2;
          f[3 * q] += F * y0, f[3 * q + 1] += F * y1, f[3 * q + 2] += F * y2;
        }
        ec[p] += e;
        ec[q] += e;
      };
      if (broken[k]) {
        vb[p] += bk * vq;
        vb[q] += bk * vp;
        // The ends of a broken bond meet again through contact only.
        if (contact && r < std::min(0.9 * r0, range)) repel(std::min(0.9 * r0, range));
        continue;
      }
      const double s = r * inv_len0[k] - 1.0;  // (r - r0)/r0 without a division
      // Micro-plastic bond (seed 001 "Micro-Elastic and -Plastic Materials"; Silling & Askari 2005):
      // elastic in s - s_p up to the yield stretch s_y, perfectly plastic beyond, elastic unloading
      // with s_p kept; plastic work c s_y |ds_p| |xi| beta V_p V_q, half to each end. Failure on s.
      double se = s;
      if constexpr (Plastic) {
        se = s - sp[k];
        double dsp = 0.0;
        if (se > sy) dsp = se - sy;
        else if (se < -sy) dsp = se + sy;
        if (dsp != 0.0) {
          sp[k] += dsp;
          // Both ends' copies (read from the lower end; a checkpoint or a ghost row needs either).
          sp[offset[q] + mirror[k]] = sp[k];
          se -= dsp;
          const double w = 0.5 * cpq * sy * std::abs(dsp) * r0 * bk * vv;
          dis[p] += w;
          dis[q] += w;
        }
      }
      // Bond energy c se^2 |xi| beta V_p V_q / 2 (Silling & Askari 2005 eq. 21, both ends' halves).
      const double u = 0.5 * cpq * se * se * r0 * bk * vv;
      if (s > std::min(s0p, s0[q])) {
        // Failure against the previous step's s0 (LAMMPS PERI's rule), for both ends at once.
        broken[k] = 1;
        broken[offset[q] + mirror[k]] = 1;
        vb[p] += bk * vq;
        vb[q] += bk * vp;
        if (lammps_break) {
          // break_rule: lammps. The bond still acts this step (LAMMPS applies the force, then
          // breaks), and its energy U(s_n+1) is what it dissipates; the next step's first half-kick
          // then carries a force whose energy is gone (LAMMPS's own O(dt) error, kept for parity).
          dis[p] += 0.5 * u;
          dis[q] += 0.5 * u;
          if (r > 0.0) {
            const double G = cpq * se * bk * vv / r;
            fx += G * y0, fy += G * y1, fz += G * y2;
            f[3 * q] -= G * y0, f[3 * q + 1] -= G * y1, f[3 * q + 2] -= G * y2;
          }
          if (alpha > 0.0) {
            smp = std::max(smp, -alpha * s);
            smax[q] = std::max(smax[q], -alpha * s);
          }
          continue;
        }
        // Default: from now on the bond exerts no force. It dissipates what the step took out of
        // the motion: velocity Verlet gave the points only the first half-kick of this bond, so the
        // energy booked is U(s_n+1) - 1/2 F (r_n+1 - r_n), the trapezoidal work of the bond over the
        // step; U(s_n+1) alone creates the missing half-kick (+7 % of the energy in a dynamic tear,
        // docs/validation.md). Half to each end.
        const double dp0 = xprev[3 * q] - xprev[3 * p], dp1 = xprev[3 * q + 1] - xprev[3 * p + 1],
                     dp2 = xprev[3 * q + 2] - xprev[3 * p + 2];
        const double r_prev = std::sqrt(dp0 * dp0 + dp1 * dp1 + dp2 * dp2);
        const double F = cpq * se * bk * vv;  // N
        const double d = 0.5 * (u - 0.5 * F * (r - r_prev));
        dis[p] += d;
        dis[q] += d;
        continue;
      }
      // f = c s (y/|y|) per unit volume of each end (seed 001 "Microelastic material"), times V_p V_q.
      if (r > 0.0) {
        const double G = cpq * se * bk * vv / r;  // the one division per bond
        fx += G * y0, fy += G * y1, fz += G * y2;
        f[3 * q] -= G * y0, f[3 * q + 1] -= G * y1, f[3 * q + 2] -= G * y2;
      }
      ep += 0.5 * u;
      energy[q] += 0.5 * u;
      if (alpha > 0.0) {  // s0_new = s00 - alpha s_min (LAMMPS PERI); unused with alpha = 0
        smp = std::max(smp, -alpha * s);
        smax[q] = std::max(smax[q], -alpha * s);
      }
      if (bonded_contact && r < std::min(0.9 * r0, range)) repel(std::min(0.9 * r0, range));
    }
    f[3 * p] += fx, f[3 * p + 1] += fy, f[3 * p + 2] += fz;
    energy[p] += ep;
    smax[p] = smp;
  }
}

}  // namespace

void bond_pass(const BondPassArgs& a, Index p0, Index p1) {
  const bool plastic = a.plastic_stretch != nullptr, surface = a.surface_factor != nullptr;
  if (plastic && surface) bond_pass_t<true, true>(a, p0, p1);
  else if (plastic) bond_pass_t<true, false>(a, p0, p1);
  else if (surface) bond_pass_t<false, true>(a, p0, p1);
  else bond_pass_t<false, false>(a, p0, p1);
}

}  // namespace ballista::pd
