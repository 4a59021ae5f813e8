#include "core/polar.hpp"

#include <cmath>

namespace ballista {

Mat3 polar_rotation(const Mat3& F, const Mat3& guess) {
  // Work on G = guess^T F; its rotation factor Rg is near I when guess is good, R = guess Rg.
  Mat3 X = transpose_times(guess, F);
  for (int it = 0; it < 30; ++it) {
    const double d = det(X);
    const Mat3 XinvT = (1.0 / d) * cofactor(X);
    // Frobenius scaling (Higham 1986, §3): zeta = sqrt(|X^-1|_F / |X|_F); skipped near convergence.
    double zeta = std::sqrt(frobenius(XinvT) / frobenius(X));
    if (std::abs(zeta - 1.0) < 1e-3) zeta = 1.0;
    Mat3 Xn = 0.5 * (zeta * X + (1.0 / zeta) * XinvT);
    double diff = frobenius(Xn - X);
    X = Xn;
    if (diff < 1e-14) break;
  }
  return guess * X;
}

void polar_decompose(const Mat3& F, Mat3& R, Mat3& U, const Mat3& guess) {
  R = polar_rotation(F, guess);
  U = sym(transpose_times(R, F));
}

}  // namespace ballista
