#pragma once
// The strain increment handed to the constitutive kernels for one step with relative deformation
// gradient dF = F_{n+1} F_n^-1 = I + G (G = dt L, thesis seed 000 eq. 4.9-4.10).
//
// Midpoint (Hughes & Winget 1980, Int. J. Numer. Meth. Eng. 15:1862-1867): the
// increment is the symmetric part of the displacement-increment gradient taken on the midpoint
// configuration x_{n+1/2} = (x_n + x_{n+1})/2,
//   d_eps = sym( G (I + G/2)^-1 ) = sym( 2 (dF - I)(dF + I)^-1 ),
// which is exactly zero when dF is a rotation (the Cayley transform 2 (Q - I)(Q + I)^-1 of a
// rotation Q is skew) and equals sym(G) + O(|G|^2) otherwise, so the rate form of thesis eq. 2.6
// is unchanged to first order. For a stretch dF = diag(lambda) it is 2 (lambda - 1)/(lambda + 1)
// = ln lambda + O((lambda - 1)^3), against lambda - 1 = ln lambda + O((lambda - 1)^2) for sym(G).
#include "core/lanes.hpp"
#include "core/tensor.hpp"

namespace ballista {

/// sym(G (I + G/2)^-1), G = dF - I (Hughes & Winget 1980). One 3x3 inverse and one product.
inline Mat3 midpoint_strain_increment(const Mat3& G) {
  const Mat3 B = Mat3::identity() + 0.5 * G;
  return sym(G * inverse(B));
}

/// The same for kLanes points (lanes.hpp): the scalar function lane by lane, to round-off.
inline Mat3L midpoint_strain_increment(const Mat3L& G) {
  const Mat3L B = Mat3L::identity() + 0.5 * G;
  return sym(G * inverse(B));
}

/// The relative deformation gradient whose midpoint increment is the symmetric `eps` with no spin:
/// dF = (I - eps/2)^-1 (I + eps/2) (the inverse of the map above; the two factors commute, so dF
/// is symmetric and 2 (dF - I)(dF + I)^-1 = eps exactly).
inline Mat3 spin_free_step_for_increment(const Mat3& eps) {
  return inverse(Mat3::identity() - 0.5 * eps) * (Mat3::identity() + 0.5 * eps);
}

}  // namespace ballista
