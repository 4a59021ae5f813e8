#include "materials/distortion.hpp"

#include <cmath>

namespace ballista {

bool remap_if_distorted(Mat3& F, double J, const Mat3& R, double limit) {
  if (!beyond_distortion_limit(F, J, limit)) return false;
  F = std::cbrt(J) * R;
  return true;
}

}  // namespace ballista
