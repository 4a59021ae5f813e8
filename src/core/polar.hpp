#pragma once
// Polar decomposition F = R U (thesis seed 000, §2.3: the unrotated frame uses R).
#include "core/tensor.hpp"

namespace ballista {

/// Rotation R of F = R U by scaled Newton iteration X <- (zeta X + X^{-T}/zeta)/2
/// (Higham, "Computing the polar decomposition", SIAM J. Sci. Stat. Comput. 7 (1986), eq. 3.3,
/// with the Frobenius-norm scaling of his §3). `guess` is a rotation close to R (for example the
/// previous step's R): the iteration then runs on guess^T F, which is near-symmetric, and
/// converges in two or three iterations. Requires det(F) > 0.
Mat3 polar_rotation(const Mat3& F, const Mat3& guess = Mat3::identity());

/// Both factors: U = R^T F (symmetrised to remove round-off).
void polar_decompose(const Mat3& F, Mat3& R, Mat3& U, const Mat3& guess = Mat3::identity());

}  // namespace ballista
