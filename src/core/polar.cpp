#include "core/polar.hpp"

#include <algorithm>
#include <cmath>

namespace ballista {

Mat3 reorthogonalise_step(const Mat3& R, const Mat3& E) {
  return R * (Mat3::identity() - 0.5 * E);
}

/// Rotation by Higham's scaled Newton iteration X <- (zeta X + X^{-T}/zeta)/2 (Higham, SIAM J.
/// Sci. Stat. Comput. 7 (1986), eq. 3.3 and the Frobenius-norm scaling of §3). Globally
/// convergent for det F > 0; used when no good guess is available.
Mat3 polar_rotation_fallback(const Mat3& F, const Mat3& guess) {
  Mat3 X = transpose_times(guess, F);
  for (int it = 0; it < 30; ++it) {
    const double d = det(X);
    const Mat3 XinvT = (1.0 / d) * cofactor(X);
    double zeta = std::sqrt(frobenius(XinvT) / frobenius(X));
    if (std::abs(zeta - 1.0) < 1e-3) zeta = 1.0;
    Mat3 Xn = 0.5 * (zeta * X + (1.0 / zeta) * XinvT);
    const double diff = frobenius(Xn - X);
    X = Xn;
    if (diff < 1e-14) break;
  }
  return reorthogonalise(guess * X);
}


void polar_decompose(const Mat3& F, Mat3& R, Mat3& U, const Mat3& guess) {
  R = polar_rotation(F, guess);
  U = sym(transpose_times(R, F));
}

}  // namespace ballista
