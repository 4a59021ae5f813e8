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
  // guess is orthogonal only to round-off, and when it is the previous step's R that error is
  // inherited and accumulates over steps (measured: |R^T R - I| ~ 3e-11 after 10^6 warm-started
  // steps, which the unrotate/rotate round trip of the stress turns into a systematic drift).
  // One unscaled Newton step on the product itself restores orthogonality to round-off
  // (quadratic convergence: an error e becomes O(e^2)).
  const Mat3 R = guess * X;
  return 0.5 * (R + inverse_transpose(R));
}

void polar_decompose(const Mat3& F, Mat3& R, Mat3& U, const Mat3& guess) {
  R = polar_rotation(F, guess);
  U = sym(transpose_times(R, F));
}

}  // namespace ballista
