#pragma once
// Distance of a point from an axis, shared by the probes (max_radius, penetration channel).
#include <cmath>

#include "core/tensor.hpp"

namespace ballista {

/// Distance of y from the line through c along `axis` (0 x, 1 y, 2 z). In 2D (nd = 2) the line
/// lies in the x-y plane: the distance is the other in-plane coordinate's offset (in
/// axisymmetric runs, with c on the axis, the radius x).
inline double distance_from_axis(const Vec3& y, const Vec3& c, int axis, int nd) {
  if (nd == 2) return axis == 1 ? std::abs(y[0] - c[0]) : std::abs(y[1] - c[1]);
  double r2 = 0.0;
  for (int k = 0; k < 3; ++k)
    if (k != axis) r2 += (y[k] - c[k]) * (y[k] - c[k]);
  return std::sqrt(r2);
}

}  // namespace ballista
