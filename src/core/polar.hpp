#pragma once
// Polar decomposition F = R U (thesis seed 000, §2.3: the unrotated frame uses R).
#include <cmath>

#include "core/tensor.hpp"

namespace ballista {

/// Rotation R of F = R U (requires det F > 0). `guess` is a rotation close to R (for example the
/// previous step's R): a Newton iteration on the rotation alone then converges in two
/// iterations (see the definition below). Inline: it runs once per point per step.
inline Mat3 polar_rotation(const Mat3& F, const Mat3& guess = Mat3::identity());

/// Higham's globally convergent scaled Newton iteration X <- (zeta X + X^{-T}/zeta)/2 (Higham,
/// "Computing the polar decomposition", SIAM J. Sci. Stat. Comput. 7 (1986), eq. 3.3, with the
/// Frobenius-norm scaling of his §3), used when the guess is poor; re-orthogonalised.
Mat3 polar_rotation_fallback(const Mat3& F, const Mat3& guess);
/// Orthogonality correction by one Newton-Schulz step (Higham, Functions of Matrices, 2008,
/// §8.3); see polar_rotation.
Mat3 reorthogonalise_step(const Mat3& R, const Mat3& E);

/// Restores orthogonality of a rotation carrying round-off. Without it a warm-started R inherits
/// the previous step's error and the error accumulates over millions of steps. With
/// E = R^T R - I the correction R (I - E/2) turns an error e into O(e^2); it is skipped while R is
/// orthogonal to 4e-15 (forming R^T R costs a few ulps, so a tighter bound would always correct).
inline Mat3 reorthogonalise(const Mat3& R) {
  const Mat3 E = transpose_times(R, R) - Mat3::identity();
  double e = 0.0;
  for (double x : E.a) e = e > std::abs(x) ? e : std::abs(x);
  if (e < 4e-15) return R;
  return reorthogonalise_step(R, E);
}

/// Both factors: U = R^T F (symmetrised to remove round-off).
void polar_decompose(const Mat3& F, Mat3& R, Mat3& U, const Mat3& guess = Mat3::identity());

inline Mat3 polar_rotation(const Mat3& F, const Mat3& guess) {
  // Newton iteration on the rotation alone. With X = guess^T F, we seek a small rotation Q with
  // Q^T X symmetric (then R = guess Q). Linearising Q = I + Theta (axial vector t):
  //   skew(X) = skew(Theta X_s)  =>  axial(skew X) = 1/2 (tr(X_s) I - X_s) t,
  // using axial(Theta S + S Theta) = (tr S I - S) t for symmetric S (e.g. Bonet & Wood,
  // Nonlinear Continuum Mechanics, 2nd ed., §2.2). Q is built by the Cayley transform, which is
  // orthogonal to round-off for any t. Quadratic convergence: a warm start from the previous
  // step's R needs two iterations. Falls back to Higham's iteration if the guess is poor.
  Mat3 X = transpose_times(guess, F);
  Mat3 Qtot = Mat3::identity();
  for (int it = 0; it < 8; ++it) {
    const double a0 = 0.5 * (X(2, 1) - X(1, 2));
    const double a1 = 0.5 * (X(0, 2) - X(2, 0));
    const double a2 = 0.5 * (X(1, 0) - X(0, 1));
    // M = tr(X_s) I - X_s (symmetric, positive definite near the solution).
    const double s01 = 0.5 * (X(0, 1) + X(1, 0)), s02 = 0.5 * (X(0, 2) + X(2, 0));
    const double s12 = 0.5 * (X(1, 2) + X(2, 1));
    const double tr = X(0, 0) + X(1, 1) + X(2, 2);
    const double m00 = tr - X(0, 0), m11 = tr - X(1, 1), m22 = tr - X(2, 2);
    const double c00 = m11 * m22 - s12 * s12, c01 = s02 * s12 + s01 * m22, c02 = s01 * s12 + s02 * m11;
    const double detM = m00 * c00 - s01 * c01 - s02 * c02;
    if (!(detM > 0.0) || !(m00 > 0.0)) return polar_rotation_fallback(F, guess);
    const double c11 = m00 * m22 - s02 * s02, c12 = m00 * s12 + s01 * s02, c22 = m00 * m11 - s01 * s01;
    // t = 2 M^{-1} a  (M^{-1} = adj(M)/det(M), M has off-diagonals -s_ij).
    const double k = 2.0 / detM;
    const double t0 = k * (c00 * a0 + c01 * a1 + c02 * a2);
    const double t1 = k * (c01 * a0 + c11 * a1 + c12 * a2);
    const double t2 = k * (c02 * a0 + c12 * a1 + c22 * a2);
    // Cayley: Q = I + 2/(1 + |h|^2) (H + H^2), h = t/2, H the skew matrix of h.
    const double h0 = 0.5 * t0, h1 = 0.5 * t1, h2 = 0.5 * t2;
    const double hh = h0 * h0 + h1 * h1 + h2 * h2;
    const double g = 2.0 / (1.0 + hh);
    Mat3 Q;
    Q(0, 0) = 1.0 + g * (h0 * h0 - hh);
    Q(1, 1) = 1.0 + g * (h1 * h1 - hh);
    Q(2, 2) = 1.0 + g * (h2 * h2 - hh);
    Q(0, 1) = g * (h0 * h1 - h2);
    Q(1, 0) = g * (h0 * h1 + h2);
    Q(0, 2) = g * (h0 * h2 + h1);
    Q(2, 0) = g * (h0 * h2 - h1);
    Q(1, 2) = g * (h1 * h2 - h0);
    Q(2, 1) = g * (h1 * h2 + h0);
    X = transpose_times(Q, X);
    Qtot = Qtot * Q;
    // Quadratic convergence: once the correction is below 1e-8 the remaining error is O(1e-16).
    if (hh < 1e-16) return reorthogonalise(guess * Qtot);
  }
  return polar_rotation_fallback(F, guess);
}


}  // namespace ballista
