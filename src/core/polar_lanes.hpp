#pragma once
// The rotation of F = R U for kLanes points at once: polar_rotation (polar.hpp) lane by lane.
#include "core/lanes.hpp"
#include "core/polar.hpp"

namespace ballista {

/// R of F = R U for each lane, warm-started from `guess` (the previous step's R): what
/// polar_rotation(F.lane(l), guess.lane(l)) returns, to round-off (lanes.hpp). The Newton iteration of polar_rotation runs
/// on all lanes together; a lane stops where the scalar loop would return (its correction below
/// 1e-8) and keeps its X and accumulated Q from then on. A lane the scalar loop would hand to
/// Higham's fallback (M not positive definite, or no convergence in 8 iterations), or whose
/// rotation needs the orthogonality correction, is finished by the scalar functions.
inline Mat3L polar_rotation(const Mat3L& F, const Mat3L& guess) {
  Mat3L X = transpose_times(guess, F);
  Mat3L Qtot = Mat3L::identity();
  LaneMask active = LaneMask{} - 1;  // every lane iterates ...
  LaneMask fallback = LaneMask{};    // ... none needs Higham's iteration yet
  for (int it = 0; it < 8 && any(active); ++it) {
    const Lane a0 = 0.5 * (X.a[7] - X.a[5]);
    const Lane a1 = 0.5 * (X.a[2] - X.a[6]);
    const Lane a2 = 0.5 * (X.a[3] - X.a[1]);
    const Lane s01 = 0.5 * (X.a[1] + X.a[3]), s02 = 0.5 * (X.a[2] + X.a[6]);
    const Lane s12 = 0.5 * (X.a[5] + X.a[7]);
    const Lane tr = X.a[0] + X.a[4] + X.a[8];
    const Lane m00 = tr - X.a[0], m11 = tr - X.a[4], m22 = tr - X.a[8];
    const Lane c00 = m11 * m22 - s12 * s12, c01 = s02 * s12 + s01 * m22, c02 = s01 * s12 + s02 * m11;
    const Lane detM = m00 * c00 - s01 * c01 - s02 * c02;
    const LaneMask bad = active & ~((detM > 0.0) & (m00 > 0.0));
    fallback |= bad;
    active &= ~bad;
    const Lane c11 = m00 * m22 - s02 * s02, c12 = m00 * s12 + s01 * s02, c22 = m00 * m11 - s01 * s01;
    const Lane k = 2.0 / detM;
    const Lane t0 = k * (c00 * a0 + c01 * a1 + c02 * a2);
    const Lane t1 = k * (c01 * a0 + c11 * a1 + c12 * a2);
    const Lane t2 = k * (c02 * a0 + c12 * a1 + c22 * a2);
    const Lane h0 = 0.5 * t0, h1 = 0.5 * t1, h2 = 0.5 * t2;
    const Lane hh = h0 * h0 + h1 * h1 + h2 * h2;
    const Lane g = 2.0 / (1.0 + hh);
    Mat3L Q;
    Q.a[0] = 1.0 + g * (h0 * h0 - hh);
    Q.a[4] = 1.0 + g * (h1 * h1 - hh);
    Q.a[8] = 1.0 + g * (h2 * h2 - hh);
    Q.a[1] = g * (h0 * h1 - h2);
    Q.a[3] = g * (h0 * h1 + h2);
    Q.a[2] = g * (h0 * h2 + h1);
    Q.a[6] = g * (h0 * h2 - h1);
    Q.a[5] = g * (h1 * h2 - h0);
    Q.a[7] = g * (h1 * h2 + h0);
    const Mat3L Xn = transpose_times(Q, X);
    const Mat3L Qn = Qtot * Q;
    for (int e = 0; e < 9; ++e) {
      X.a[e] = select(active, Xn.a[e], X.a[e]);
      Qtot.a[e] = select(active, Qn.a[e], Qtot.a[e]);
    }
    active &= ~(hh < 1e-16);
  }
  fallback |= active;  // not converged in 8 iterations
  // reorthogonalise(guess * Qtot), its test lane-wise.
  Mat3L R = guess * Qtot;
  const Mat3L E = transpose_times(R, R) - Mat3L::identity();
  Lane e = splat(0.0);
  for (int k = 0; k < 9; ++k) {
    const Lane x = E.a[k];
    const Lane ax = select(x < 0.0, -x, x);  // |x| (the signs of -0 and NaN do not matter below)
    e = select(e > ax, e, ax);
  }
  const LaneMask orthogonal = e < 4e-15;
  for (int l = 0; l < kLanes; ++l) {
    if (fallback[l])
      R.set_lane(l, polar_rotation(F.lane(l), guess.lane(l)));
    else if (!orthogonal[l])
      R.set_lane(l, reorthogonalise_step(R.lane(l), E.lane(l)));
  }
  return R;
}

}  // namespace ballista
