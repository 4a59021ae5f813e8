#include "analysis/hole_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ballista {

std::vector<double> wall_radii(const std::vector<LateralPoint>& points, double axial_lo, double axial_hi, int bins,
                               LateralGeometry geometry, const WallOptions& o) {
  if (bins < 1 || !(axial_hi > axial_lo) || !(o.dr > 0.0) || o.sustain < 1)
    throw std::invalid_argument("wall_radii: bins >= 1, axial_hi > axial_lo, dr > 0 and sustain >= 1 expected");
  const double dz = (axial_hi - axial_lo) / bins;
  double r_max = 0.0;
  for (const LateralPoint& p : points)
    if (std::isfinite(p.lateral)) r_max = std::max(r_max, p.lateral + p.half_width);
  const int rings = static_cast<int>(std::ceil(r_max / o.dr)) + 1;
  std::vector<double> fill(static_cast<std::size_t>(bins) * rings, 0.0);
  for (const LateralPoint& p : points) {
    if (!(p.axial >= axial_lo && p.axial < axial_hi) || !std::isfinite(p.lateral)) continue;
    const int b = std::min(static_cast<int>((p.axial - axial_lo) / dz), bins - 1);
    double* f = &fill[static_cast<std::size_t>(b) * rings];
    // The point's volume spread evenly over [r - w, r + w] (folded at the axis).
    const double lo = std::max(0.0, p.lateral - p.half_width), hi = p.lateral + p.half_width;
    if (!(hi > lo)) {
      f[std::min(static_cast<int>(p.lateral / o.dr), rings - 1)] += p.volume;
      continue;
    }
    const double density = p.volume / (hi - lo);
    for (int k = static_cast<int>(lo / o.dr); k < rings && k * o.dr < hi; ++k) {
      const double overlap = std::min(hi, (k + 1) * o.dr) - std::max(lo, k * o.dr);
      if (overlap > 0.0) f[k] += density * overlap;
    }
  }
  // The volume of annulus k of an axial bin, in the points' own measure.
  auto annulus = [&](int k) {
    const double r_mid = (k + 0.5) * o.dr;
    switch (geometry) {
      case LateralGeometry::Axisymmetric: return r_mid * o.dr * dz;  // per radian
      case LateralGeometry::ThreeD: return 2.0 * std::numbers::pi * r_mid * o.dr * dz;
      case LateralGeometry::PlaneStrain: return 2.0 * o.dr * dz;  // both sides of the line
    }
    return 0.0;
  };
  std::vector<double> out(static_cast<std::size_t>(bins), std::numeric_limits<double>::quiet_NaN());
  for (int b = 0; b < bins; ++b) {
    const double* f = &fill[static_cast<std::size_t>(b) * rings];
    for (int k = 0; k + o.sustain <= rings; ++k) {
      bool wall = true;
      for (int j = k; j < k + o.sustain && wall; ++j) wall = f[j] >= o.threshold * annulus(j);
      if (wall) {
        // Within the annuli: the fraction's profile, linear between the centres of annulus k - 1
        // (below the threshold, else it would have been the wall) and annulus k, crosses the
        // threshold here. A sharp wall is then found within about a tenth of an annulus instead
        // of anywhere in the annulus by its inner edge (test_hole_profile.cpp).
        double r = k * o.dr;
        if (k > 0) {
          const double below = f[k - 1] / annulus(k - 1), at = f[k] / annulus(k);
          const double s = at > below ? (o.threshold - below) / (at - below) : 1.0;
          r = (k - 0.5 + std::clamp(s, 0.0, 1.0)) * o.dr;
        }
        out[b] = r;
        break;
      }
    }
  }
  return out;
}

}  // namespace ballista
