// A6 finite-difference tangent check (verification CATALOGUE A6; PointResult::tangent in
// materials/material.hpp: d sigma_bar_{n+1} / d eps, eps = D_bar dt, 6x6 in the order 11, 22, 33,
// 23, 13, 12 with tensor shear strains).
//
// How the strain increment is perturbed. The 6x6 d sigma_bar / d eps is defined for a pure strain
// increment: a spin-free step whose unrotated increment is eps. The adapter hands the model the
// midpoint increment of dF = F_{n+1} F_n^-1 (Hughes & Winget 1980; materials/strain_increment.hpp),
// sym(2 (dF - I)(dF + I)^-1), unrotated by R_{n+1}. At a check step the point holds
// (F_n, R_n, sigma_n, state_n) and the path's own step has that increment eps0. Each evaluation
// with eps = eps0 +- h E_j (E_j the unit tensor of component j) goes to
//     F(eps) = R S(eps) R^T F_n,  S(eps) = (I - eps/2)^-1 (I + eps/2),  R = polar rotation of F(eps)
//                                      (a fixed point, found by iterating
//                                      R <- polar(R S R^T F_n); it contracts by ~|eps| per iteration),
// S being the symmetric stretch whose midpoint increment is exactly eps; so L dt = R (S - I) R^T is
// symmetric, the adapter's D_bar dt = R^T (R eps R^T) R = eps exactly, and J_{n+1} = J_n det(S):
// every input of the kernel (D_bar, J, F_{n+1}, F_old) moves as in a real spin-free step, so
// hypoelastic, EOS and hyperelastic kernels see the same perturbation.
// (Holding R fixed instead would change the spin with eps and J by O(h |spin|), a 1e-5 effect on an
// EOS tangent that is not part of d sigma_bar / d eps.)
//
// Central differences with h = 1e-7: the truncation error h^2/6 |sigma'''| / |sigma'| is
// ~(h / yield strain)^2 ~ 1e-9 away from kinks (the return map curves on the scale of the yield
// strain, >= 1e-3), and round-off is ~1e-16 |sigma| / h relative to |sigma'| ~ 1e-9 (measured
// 2e-9 to 4e-8 for consistent J2 tangents). Tolerance 1e-6 (relative Frobenius norm of the 6x6
// difference) is 25-500x that and far below the 0.2..1 errors of a continuum tangent used as the
// algorithmic one, a missing factor 2 on shears or a wrong modulus. The truncation error of each
// sample is estimated from the same differences with 2h (|T_fd(h) - T_fd(2h)| = 3 x the h^2 error);
// a sample where that estimate exceeds 3e-7 (its finite difference could be off by a tenth of
// the tolerance: the step is near or across a kink such as yield onset or a cutoff, where the
// tangent is one-sided by nature) is skipped and reported as such.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/polar.hpp"
#include "materials/strain_increment.hpp"
#include "verify/a6_objectivity.hpp"
#include "verify/hook_material.hpp"
#include "materials/point_batch.hpp"

namespace ballista {

namespace {

constexpr double kSmoothLimit = 3e-7;  ///< |T_fd(h) - T_fd(2h)| / |T_fd| above which a sample is skipped
constexpr int kI[6] = {0, 1, 2, 1, 0, 0};
constexpr int kJ[6] = {0, 1, 2, 2, 2, 1};

/// Unit symmetric tensor of component k (tensor shear: both off-diagonal entries 1).
Mat3 unit_sym(int k) {
  Mat3 E;
  E(kI[k], kJ[k]) = 1.0;
  E(kJ[k], kI[k]) = 1.0;
  return E;
}

/// The spin-free step F = R S(eps) R^T F_n with R its own polar rotation (see above); `guess`
/// starts the fixed-point iteration.
Mat3 spin_free_step(const Mat3& F_n, const Mat3& eps, const Mat3& guess) {
  Mat3 R = guess;
  const Mat3 A = spin_free_step_for_increment(eps);
  for (int it = 0; it < 100; ++it) {
    const Mat3 R_next = polar_rotation(rotate(R, A) * F_n, R);
    const double change = frobenius(R_next - R);
    R = R_next;
    if (change < 1e-15) break;
  }
  return rotate(R, A) * F_n;
}

struct TangentSample {
  bool filled = false, partial = false, smooth = true;
  double err = 0.0, smooth_err = 0.0;
  double model[36], fd[36];
};

/// The check at one step of point p of `path_batch`, stepping to F_new over dt.
TangentSample check_step(const Material& m, PointBatch& path_batch, Index p, const Mat3& F_new, double dt, double h) {
  // Points: 0 base (tangent read), 1-6 +h, 7-12 -h, 13-18 +2h, 19-24 -2h.
  PointBatch b(m, 25);
  const Mat3 F_n = path_batch.F(p);
  const Mat3 R0 = polar_rotation(F_new, path_batch.R(p));
  const Mat3 eps0 = unrotate_sym(R0, midpoint_strain_increment(F_new * inverse(F_n) - Mat3::identity()));
  Mat3 targets[25];
  targets[0] = spin_free_step(F_n, eps0, R0);
  for (int j = 0; j < 6; ++j) {
    const Mat3 E = unit_sym(j);
    targets[1 + j] = spin_free_step(F_n, eps0 + h * E, R0);
    targets[7 + j] = spin_free_step(F_n, eps0 - h * E, R0);
    targets[13 + j] = spin_free_step(F_n, eps0 + 2.0 * h * E, R0);
    targets[19 + j] = spin_free_step(F_n, eps0 - 2.0 * h * E, R0);
  }
  for (Index q = 0; q < 25; ++q) {
    b.copy_point(path_batch, p, q);
    b.set_F_eq410(q, targets[q], dt);
  }
  std::vector<double> tangent(25 * 36, std::numeric_limits<double>::quiet_NaN());
  b.step(dt, tangent.data());
  TangentSample s;
  int nfilled = 0;
  for (int k = 0; k < 36; ++k) {
    s.model[k] = tangent[k];
    if (!std::isnan(tangent[k])) ++nfilled;
  }
  s.filled = nfilled > 0;
  s.partial = nfilled > 0 && nfilled < 36;
  double n_fd = 0.0, n_diff = 0.0, n_smooth = 0.0;
  for (int j = 0; j < 6; ++j) {
    const Mat3 dp = b.stress_bar(1 + j) - b.stress_bar(7 + j);
    const Mat3 dp2 = b.stress_bar(13 + j) - b.stress_bar(19 + j);
    for (int i = 0; i < 6; ++i) {
      const double fd = dp(kI[i], kJ[i]) / (2.0 * h);
      const double fd2 = dp2(kI[i], kJ[i]) / (4.0 * h);
      s.fd[6 * i + j] = fd;
      n_fd += fd * fd;
      n_smooth += (fd - fd2) * (fd - fd2);
      if (s.filled) n_diff += (s.model[6 * i + j] - fd) * (s.model[6 * i + j] - fd);
    }
  }
  n_fd = std::sqrt(n_fd);
  s.smooth_err = n_fd > 0.0 ? std::sqrt(n_smooth) / n_fd : 0.0;
  s.smooth = s.smooth_err <= kSmoothLimit;
  s.err = n_fd > 0.0 ? std::sqrt(n_diff) / n_fd : (n_diff > 0.0 ? 1.0 : 0.0);
  return s;
}

}  // namespace

VerifyCase run_a6_tangent(const MaterialFactory& f, const A6Problem& pb) {
  const std::string title = "A6 tangent: algorithmic tangent vs central differences of the stress update";
  if (!f.example) return VerifyCase::not_applicable(f.model, "A6-tangent", title, "model has no example hook");
  const auto mat = make_hook_material(f, f.example(), "example");

  std::mt19937_64 rng(pb.seed);  // the same paths as the objectivity check
  std::vector<RandomFPath> paths;
  for (int i = 0; i < pb.paths; ++i) {
    paths.push_back(random_F_path(rng, pb));
    for (int k = 0; k < pb.constant_rotations + pb.rotating_copies; ++k)
      (void)random_rotation(rng, pb.duration, k >= pb.constant_rotations);
  }
  PointBatch b(*mat, pb.paths);
  for (Index p = 0; p < pb.paths; ++p) b.stress(p) = mat->initial_stress(Mat3::identity());
  const int N = pb.steps();
  const double dt = pb.dt();
  const int every = std::max(1, N / pb.tangent_checks_per_path);
  std::vector<TangentSample> samples;
  std::vector<double> sample_step, sample_path;
  for (int step = 1; step <= N; ++step) {
    if ((step + every / 2) % every == 0) {
      for (Index p = 0; p < pb.paths; ++p) {
        samples.push_back(check_step(*mat, b, p, paths[p].at_step(step), dt, pb.fd_step));
        sample_step.push_back(step);
        sample_path.push_back(static_cast<double>(p));
        if (!samples.front().filled)
          return VerifyCase::not_applicable(f.model, "A6-tangent", title,
                                            "no tangent: the model does not fill PointResult::tangent");
      }
    }
    for (Index p = 0; p < pb.paths; ++p) b.set_F_eq410(p, paths[p].at_step(step), dt);
    b.step(dt);
  }

  VerifyCase c;
  c.model = f.model;
  c.test = "A6-tangent";
  c.title = title;
  c.plot = "a6_tangent";
  const double tol = 1e-6;
  double err = 0.0;
  int used = 0, unfilled = 0, partial = 0;
  std::vector<double> fd_all, model_all, errs, smooth_errs;
  for (const TangentSample& s : samples) {
    if (!s.filled) ++unfilled;
    if (s.partial) ++partial;
    errs.push_back(s.err);
    smooth_errs.push_back(s.smooth_err);
    if (!s.filled || !s.smooth) continue;
    ++used;
    err = std::max(err, s.err);
    for (int k = 0; k < 36; ++k) {
      fd_all.push_back(s.fd[k]);
      model_all.push_back(s.model[k]);
    }
  }
  c.max_rel_error = used > 0 ? err : std::numeric_limits<double>::quiet_NaN();
  c.tolerance = tol;
  c.error_measure = "max over smooth samples of |T_model - T_fd|_F / |T_fd|_F (6x6, central differences, h = 1e-7)";
  c.tolerance_justification =
      "central differences with h = 1e-7: truncation ~(h / yield strain)^2 ~ 1e-9, round-off ~1e-9 (measured "
      "up to 4e-8); 1e-6 is far below a continuum-for-algorithmic (0.2) or factor-2 shear error; samples whose "
      "h vs 2h differences disagree by > 3e-7 (near a kink) are skipped";
  c.check("tangent vs central differences (smooth samples)", c.max_rel_error, tol);
  c.check("samples where the tangent was filled (fraction)",
          1.0 - static_cast<double>(unfilled) / samples.size(), 1.0, true);
  c.check("samples with a completely filled 6x6 (partial ones)", partial, 0.0);
  c.check("smooth samples checked (count, >= 1)", used, 1.0, true);
  c.series = {{"fd", fd_all}, {"model", model_all}, {"sample_error", errs}, {"sample_smoothness", smooth_errs},
              {"sample_step", sample_step}, {"sample_path", sample_path}};
  c.scalars = {{"fd_step", pb.fd_step}, {"samples", static_cast<double>(samples.size())}, {"used", used},
               {"smooth_limit", kSmoothLimit}};
  c.finish();
  return c;
}

}  // namespace ballista
