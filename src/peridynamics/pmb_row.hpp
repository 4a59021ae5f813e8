#pragma once
// The hot loop of bond-based peridynamics: one point's row of PMB bonds, branch-free (broken bonds
// masked, failures only flagged) so that it can vectorise. Measured on this machine's AMD EPYC
// (docs/performance.md): the AVX-512 version (gathers of the neighbours' positions) runs at the
// speed of the scalar one, ~160 M bond evaluations per second per core, even with the whole
// problem in L2: the gathers and the sqrt/div per bond bound it. It sits in a plain function of
// raw pointers because GCC does not vectorise the loop inside the solver's lambda at all.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace ballista::pd {

struct RowSums {
  double fx = 0.0, fy = 0.0, fz = 0.0;  ///< sum of coef s y/|y| over the intact bonds, N/m^3
  double energy = 0.0;                  ///< sum of coef s^2 |xi| over the intact bonds (x 1/4: W_p), J/m^3
  double smax = -std::numeric_limits<double>::infinity();  ///< max of -alpha s over the intact bonds
  int breaks = 0;  ///< some intact bond is stretched beyond min(s0_p, s0_q)
  int touch = 0;   ///< some intact bond is shorter than min(0.9 |xi|, range) (bonded contact on)
};

/// Bonds k0 .. k1 of the point at (xp0, xp1, xp2): x as 3n doubles, the bond arrays of BondFamily,
/// coef = c beta V_q per bond, s0 of every point and s0p of this one. The force of a bond is
/// c s (y/|y|) per unit volume of each end (seed 001 "Microelastic material"; Silling & Askari 2005
/// eq. 22 with coef = c beta V_q), s = (|y| - |xi|)/|xi|.
inline RowSums pmb_row(std::int64_t k0, std::int64_t k1, const double* xs, double xp0, double xp1, double xp2,
                       const std::int32_t* other, const std::uint8_t* broken, const double* len0, const double* coef,
                       const double* s0, double s0p, double alpha, int bonded_contact, double range) {
  constexpr double kNegInf = -std::numeric_limits<double>::infinity();
  double fx = 0.0, fy = 0.0, fz = 0.0, en = 0.0, smx = kNegInf;
  int breaks = 0, touch = 0;
#pragma omp simd reduction(+ : fx, fy, fz, en) reduction(max : smx) reduction(| : breaks, touch)
  for (std::int64_t k = k0; k < k1; ++k) {
    const std::int64_t q = other[k];
    const double alive = broken[k] ? 0.0 : 1.0;
    const double y0 = xs[3 * q] - xp0, y1 = xs[3 * q + 1] - xp1, y2 = xs[3 * q + 2] - xp2;
    const double r = std::sqrt(y0 * y0 + y1 * y1 + y2 * y2), r0 = len0[k];
    const double s = (r - r0) / r0;
    breaks |= (alive > 0.0) & (s > std::min(s0p, s0[q]));
    touch |= bonded_contact & (alive > 0.0) & (r < std::min(0.9 * r0, range));
    const double g = r > 0.0 ? alive * coef[k] * s / r : 0.0;
    fx += g * y0;
    fy += g * y1;
    fz += g * y2;
    en += alive * coef[k] * s * s * r0;
    smx = std::max(smx, alive > 0.0 ? -alpha * s : kNegInf);  // s0_new = s00 - alpha s_min (LAMMPS PERI)
  }
  return {fx, fy, fz, en, smx, breaks, touch};
}

}  // namespace ballista::pd
