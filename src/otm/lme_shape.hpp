#pragma once
// Local max-entropy (LME) shape functions (Arroyo & Ortiz, IJNME 65 (2006) 2167; seed 003
// SAND2020-9716 eq. 2.12), the interpolation of the OTM solver.
//
// For a point x and its support nodes x_a, with d_a = x - x_a:
//   f_a(lambda) = -beta |d_a|^2 + lambda . d_a,   Z = sum_a exp f_a,   N_a = exp f_a / Z,
//   lambda*     = argmin_lambda log Z(lambda)      (convex; Arroyo & Ortiz 2006 eq. 20),
// so that at lambda* the gradient r = d log Z/d lambda = sum_a N_a d_a vanishes: first-order
// consistency, sum_a N_a x_a = x, besides the partition of unity. The Hessian is
// J = sum_a N_a d_a (x) d_a - r (x) r, and at lambda* the shape function gradients are
// grad N_a = -N_a J^-1 d_a (Arroyo & Ortiz 2006 eq. 23, for a constant beta).
//
// Which distance: the seed's eq. 2.12 prints -beta |X_p - X_a| (not squared); its own definition
// beta = gamma/h^2 (Fig. 5-5 caption) makes beta|d|^2 dimensionless, so the exponent is the squared
// distance of Arroyo & Ortiz, used here.
//
// lambda* by Newton's method with a backtracking (Armijo) line search on log Z, which the seed
// (ch. 5, Fig. 5-5) finds makes every solver succeed; if Newton stalls (a singular or indefinite
// step, or no decrease), Levenberg-Marquardt steps (J + mu I) s = -r with an adaptive mu take over.
// Everything is done in units of the length h (d_a / h), so the tolerances are scale-free.
#include "core/tensor.hpp"

namespace ballista::otm {

struct LmeOptions {
  double tolerance = 1e-12;  ///< converged when |r| <= tolerance h (the gradients are exact at r = 0 only)
  int max_newton = 60;       ///< Newton iterations before the fallback
  int max_fallback = 400;    ///< Levenberg-Marquardt iterations
  bool line_search = true;   ///< backtracking on log Z (false: full Newton steps, for the seed's Fig. 5-5 study)
  bool fallback = true;      ///< Levenberg-Marquardt when Newton stalls
};

struct LmeResult {
  bool converged = false;
  bool used_fallback = false;
  int iterations = 0;       ///< Newton + fallback iterations
  double residual = 0.0;    ///< |r| / h at the end
  double condition = 0.0;   ///< condition number of J (largest / smallest eigenvalue; inf if singular)
};

/// Shape functions N[0..count) and gradients dN of the point x with respect to x, from the offsets
/// d[a] = x - x_a of its support nodes (z ignored when dim == 2). beta = gamma / h^2 (1/m^2); h is
/// the length that scales the tolerances. `lambda` is the starting guess in and the solution out
/// (1/m; zero is a good start). On failure N and dN are left unspecified and converged is false.
LmeResult lme_shape(int dim, const Vec3* d, int count, double beta, double h, Vec3& lambda, double* N, Vec3* dN,
                    const LmeOptions& options = {});

/// Smallest and largest eigenvalue of the symmetric dim x dim block of A.
void symmetric_extremes(const Mat3& A, int dim, double& lo, double& hi);

/// Eigenvalues-based condition number of the symmetric dim x dim block of A (inf if singular).
double symmetric_condition(const Mat3& A, int dim);

}  // namespace ballista::otm
