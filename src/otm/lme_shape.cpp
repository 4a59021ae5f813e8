#include "otm/lme_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ballista::otm {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// log Z, the weights w_a = exp(f_a - fmax) / sum (the shape functions), r and J, all in units of
/// h (s_a = d_a / h, mu = lambda h, b = beta h^2): f_a = -b |s_a|^2 + mu . s_a.
struct Eval {
  double logz = 0.0;
  Vec3 r;
  Mat3 J;
};

Eval evaluate(int dim, const Vec3* s, int count, double b, const Vec3& mu, double* w) {
  double fmax = -kInf;
  for (int a = 0; a < count; ++a) {
    const double f = -b * dot(s[a], s[a]) + dot(mu, s[a]);
    w[a] = f;
    fmax = std::max(fmax, f);
  }
  double z = 0.0;
  for (int a = 0; a < count; ++a) {
    w[a] = std::exp(w[a] - fmax);  // shifted by the largest exponent: no overflow
    z += w[a];
  }
  Eval e;
  e.logz = fmax + std::log(z);
  const double iz = 1.0 / z;
  for (int a = 0; a < count; ++a) {
    w[a] *= iz;
    e.r += w[a] * s[a];
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) e.J(i, j) += w[a] * s[a][i] * s[a][j];
  }
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) e.J(i, j) -= e.r[i] * e.r[j];
  return e;
}

/// Solves A x = y for the dim x dim block (the unused rows of a 2D problem padded with identity);
/// false if the block is singular or not positive.
bool solve(const Mat3& A, const Vec3& y, int dim, Vec3& x) {
  Mat3 M = A;
  if (dim == 2) {
    M(2, 2) = 1.0;
    M(0, 2) = M(2, 0) = M(1, 2) = M(2, 1) = 0.0;
  }
  const double dt = det(M);
  if (!(std::abs(dt) > 0.0) || !std::isfinite(dt)) return false;
  x = inverse(M) * y;
  if (dim == 2) x[2] = 0.0;
  return all_finite(x);
}

}  // namespace

void symmetric_extremes(const Mat3& A, int dim, double& lo, double& hi) {
  if (dim == 2) {
    // Eigenvalues of a symmetric 2x2: mean +- sqrt(((a - d)/2)^2 + b^2).
    const double m = 0.5 * (A(0, 0) + A(1, 1));
    const double q = std::hypot(0.5 * (A(0, 0) - A(1, 1)), A(0, 1));
    lo = m - q;
    hi = m + q;
  } else {
    // Trigonometric solution for a symmetric 3x3 (Smith, Commun. ACM 4 (1961) 168).
    const double p1 = A(0, 1) * A(0, 1) + A(0, 2) * A(0, 2) + A(1, 2) * A(1, 2);
    const double q = trace(A) / 3.0;
    if (p1 == 0.0) {
      lo = std::min({A(0, 0), A(1, 1), A(2, 2)});
      hi = std::max({A(0, 0), A(1, 1), A(2, 2)});
    } else {
      const double p2 = (A(0, 0) - q) * (A(0, 0) - q) + (A(1, 1) - q) * (A(1, 1) - q) + (A(2, 2) - q) * (A(2, 2) - q) +
                        2.0 * p1;
      const double p = std::sqrt(p2 / 6.0);
      const Mat3 B = (1.0 / p) * (A - Mat3::diag(q, q, q));
      const double rr = std::clamp(0.5 * det(B), -1.0, 1.0);
      const double phi = std::acos(rr) / 3.0;
      hi = q + 2.0 * p * std::cos(phi);
      lo = q + 2.0 * p * std::cos(phi + 2.0 * std::numbers::pi / 3.0);
    }
  }
}

double symmetric_condition(const Mat3& A, int dim) {
  double lo, hi;
  symmetric_extremes(A, dim, lo, hi);
  if (!(lo > 0.0)) return kInf;
  return hi / lo;
}

LmeResult lme_shape(int dim, const Vec3* d, int count, double beta, double h, Vec3& lambda, double* N, Vec3* dN,
                    const LmeOptions& opt) {
  LmeResult res;
  if (count < dim + 1) {
    res.condition = kInf;
    return res;
  }
  const double inv_h = 1.0 / h;
  const double b = beta * h * h;
  // Scaled offsets; dN holds them until the gradients overwrite it at the end.
  Vec3* s = dN;
  for (int a = 0; a < count; ++a) {
    s[a] = inv_h * d[a];
    if (dim == 2) s[a][2] = 0.0;
  }
  Vec3 mu = h * lambda;
  if (dim == 2) mu[2] = 0.0;
  Eval e = evaluate(dim, s, count, b, mu, N);
  auto done = [&](const Eval& ev) { return norm(ev.r) <= opt.tolerance; };

  // Newton with backtracking on log Z (Armijo, c = 1e-4; Nocedal & Wright, Numerical Optimization,
  // Alg. 3.1), at most 40 halvings.
  bool stalled = false;
  while (!done(e) && res.iterations < opt.max_newton) {
    ++res.iterations;
    Vec3 step;
    if (!solve(e.J, -1.0 * e.r, dim, step)) { stalled = true; break; }
    const double slope = dot(e.r, step);
    if (!(slope < 0.0)) { stalled = true; break; }  // not a descent direction: J not positive definite
    double t = 1.0;
    Eval trial = evaluate(dim, s, count, b, mu + step, N);
    if (opt.line_search) {
      int halvings = 0;
      // Near lambda* the decrease falls below the round-off of log Z: allow that much.
      const double noise = 1e-14 * (1.0 + std::abs(e.logz));
      while (!(trial.logz <= e.logz + 1e-4 * t * slope + noise) && halvings < 40) {
        t *= 0.5;
        ++halvings;
        trial = evaluate(dim, s, count, b, mu + t * step, N);
      }
      if (halvings == 40) { stalled = true; e = evaluate(dim, s, count, b, mu, N); break; }
    } else if (!std::isfinite(trial.logz)) {
      stalled = true;
      e = evaluate(dim, s, count, b, mu, N);
      break;
    }
    mu = mu + t * step;
    e = trial;
  }

  // Levenberg-Marquardt fallback (Nocedal & Wright ch. 10.3): (J + m I) s = -r, m shrunk after a
  // step that lowers log Z and grown after one that does not.
  if (!done(e) && (stalled || res.iterations >= opt.max_newton) && opt.fallback) {
    res.used_fallback = true;
    double damp = 1e-3 * std::max(trace(e.J), 1e-12);
    for (int k = 0; k < opt.max_fallback && !done(e); ++k) {
      ++res.iterations;
      Mat3 A = e.J;
      for (int i = 0; i < dim; ++i) A(i, i) += damp;
      Vec3 step;
      if (!solve(A, -1.0 * e.r, dim, step)) { damp *= 10.0; continue; }
      const Eval trial = evaluate(dim, s, count, b, mu + step, N);
      if (trial.logz < e.logz) {
        mu = mu + step;
        e = trial;
        damp = std::max(damp / 3.0, 1e-14);
      } else {
        damp *= 4.0;
        e = evaluate(dim, s, count, b, mu, N);  // N back to the current mu
      }
    }
  }

  res.residual = norm(e.r);
  res.condition = symmetric_condition(e.J, dim);
  res.converged = done(e) && std::isfinite(res.condition);
  if (!res.converged) return res;
  lambda = inv_h * mu;
  // grad N_a = -N_a J^-1 d_a (Arroyo & Ortiz 2006 eq. 23); J is in units of h^2, so in SI
  // J_SI^-1 d_a = (1/h) J^-1 s_a.
  Mat3 M = e.J;
  if (dim == 2) {
    M(2, 2) = 1.0;
    M(0, 2) = M(2, 0) = M(1, 2) = M(2, 1) = 0.0;
  }
  const Mat3 Ji = inverse(M);
  for (int a = 0; a < count; ++a) {
    Vec3 g = Ji * s[a];
    if (dim == 2) g[2] = 0.0;
    dN[a] = (-N[a] * inv_h) * g;
  }
  return res;
}

}  // namespace ballista::otm
