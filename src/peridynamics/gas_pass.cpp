#include "peridynamics/gas_pass.hpp"

#include <algorithm>
#include <cmath>

namespace ballista::pd {

namespace {

/// (r/p)^m for m = 1 without a pow, the current length floored (kGasMinStretchRatio).
inline double length_ratio(double r, double p) { return r / std::max(p, kGasMinStretchRatio * r); }

inline double current_length(const GasPassArgs& a, Index i, Index j) {
  Vec3 y = a.x[j] - a.x[i];
  if (a.dim == 2) y[2] = 0.0;
  return norm(y);
}

}  // namespace

double density_measure(const GasPassArgs& a, Index i) {
  static_assert(kGasExponent == 1.0, "length_ratio is (r/p)^m for m = 1");
  const BondFamily& f = *a.family;
  double s = 0.0;
  for (Index k = f.offset[i]; k < f.offset[i + 1]; ++k) {
    const Index j = f.other[k];
    s += f.volume_factor[k] * a.vol0[j] * length_ratio(f.length0[k], current_length(a, i, j));
  }
  if (!(a.family_volume[i] > 0.0)) return 1.0;  // no neighbours: nothing to measure (one lone point)
  s /= a.family_volume[i];
  // X = S^(-d/m); S >= S_min keeps X <= kGasMaxExpansion.
  const double s_min = std::pow(kGasMaxExpansion, -kGasExponent / a.dim);
  return std::pow(std::max(s, s_min), -a.dim / kGasExponent);
}

Vec3 gas_force(const GasPassArgs& a, Index p) {
  const BondFamily& f = *a.family;
  Vec3 out;
  const bool p_gas = a.gas[p] != 0;
  const double gp = p_gas ? a.g[p] : 0.0;
  for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) {
    const Index q = f.other[k];
    const double gq = a.gas[q] ? a.g[q] : 0.0;
    // The bond's push from each gas end (gas_pass.hpp): summed in the same order at both ends, so
    // the two ends get equal and opposite forces to the last bit.
    const double t = (gp * a.vol0[q] + gq * a.vol0[p]) * f.volume_factor[k];
    if (t == 0.0) continue;
    Vec3 y = a.x[q] - a.x[p];
    if (a.dim == 2) y[2] = 0.0;
    const double r = f.length0[k], len = norm(y);
    if (len == 0.0) continue;  // coincident points: no direction to push along
    const double pl = std::max(len, kGasMinStretchRatio * r);
    // |f| = t r^m / p^(m+1) along -y (away from q), m = 1.
    out += (-t * r / (pl * pl * len)) * y;
  }
  return out;
}

double gas_inverse_length_sum(const GasPassArgs& a, Index p) {
  const BondFamily& f = *a.family;
  double s = 0.0;
  for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) s += f.volume_factor[k] * a.vol0[f.other[k]] / f.length0[k];
  return s;
}

}  // namespace ballista::pd
