// Compressible neo-Hookean hyperelasticity (Simo & Pister 1984; Bonet & Wood, Nonlinear Continuum
// Mechanics for Finite Element Analysis, 2nd ed. 2008, §6.4.3, eq. 6.28):
//   W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2
//   sigma = [lambda ln J I + mu (F F^T - I)] / J              (verification CATALOGUE B1)
// Being hyperelastic, the stress is a function of F_new alone: the kernel writes the unrotated
// stress directly, sigma_bar = R^T sigma R = [lambda ln J I + mu (C - I)] / J with C = F^T F
// (R^T F F^T R = U U = C), and ignores D_bar and the stress at t_n. Objectivity is exact.
// lambda = K - 2G/3, mu = G (small-strain limit is isotropic linear elasticity with K, G).
//
// Algorithmic tangent (PointResult::tangent, d sigma_bar_{n+1}/d eps, eps = D_bar dt), the exact
// derivative of what the kernel computes for a spin-free increment F_{n+1} = R A R^T F_n,
// R = R_{n+1} its own polar rotation (the convention of material.hpp and the A6 check), where A is
// the stretch step whose midpoint increment (materials/strain_increment.hpp) is eps:
// A = (I - eps/2)^-1 (I + eps/2), dA = (1/2)(I - eps/2)^-1 d eps (I + A). Then
// U_{n+1} = R^T F_{n+1} = A M with M = R^T F_n; perturbing eps rotates R too,
// dM = Omega M with Omega = -R^T dR skew, fixed by the symmetry of
//   dU = dA M + A Omega M                                      (3 linear equations for Omega),
// and with C = U^2, J = det U:  dC = dU U + U dU,  dJ/J = tr(U^-1 dU) = tr(A^-1 dA),
//   d sigma_bar = [mu dC + lambda (dJ/J) I] / J - sigma_bar dJ/J
// (differentiating sigma_bar = [lambda ln J I + mu (C - I)] / J). For F_n = I this is the
// derivative of Bonet & Wood (2008) eq. 6.28 along U = I + eps, no rotation.
#include <algorithm>
#include <cmath>

#include "materials/elastic_constants.hpp"
#include "materials/material_adapter.hpp"
#include "materials/strain_increment.hpp"

namespace ballista {

struct NeoHookean {
  static constexpr const char* kName = "neo_hookean";
  struct Params {
    double density = 0;  ///< rho0, kg/m^3
    double lambda = 0;   ///< first Lame constant K - 2G/3, Pa
    double mu = 0;       ///< shear modulus G, Pa
  };
  static std::vector<ParamSpec> param_specs() { return elastic_param_specs(); }
  static Params make(const ParamValues& v) {
    const ElasticConstants e = elastic_constants_from(v);
    return {v.at("density"), e.bulk - 2.0 * e.shear / 3.0, e.shear};
  }
  // Verification hooks (MaterialFactory): rubber-like example (nu = 0.45) at large strain.
  static ParamValues example_params() { return {{"density", 1100.0}, {"bulk_modulus", 40e6}, {"shear_modulus", 4e6}}; }
  static ParamValues reduce_to_elastic(double rho, double K, double G) {
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}};
  }

  static std::vector<StateFieldSpec> state_fields() { return {}; }

  /// [lambda ln J I + mu (B - I)] / J for B = F F^T (spatial) or B = C = F^T F (unrotated).
  static Mat3 stress_from(const Params& p, const Mat3& B, double J) {
    Mat3 s = (p.mu / J) * B;
    const double iso = (p.lambda * std::log(J) - p.mu) / J;
    s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
    return s;
  }

  /// Spatial Cauchy stress for deformation gradient F (used for prestressed starts).
  static Mat3 initial_stress(const Params& p, const Mat3& F) {
    return stress_from(p, times_transpose(F, F), det(F));
  }

  static void update(const Params& p, const PointKinematics& k, Mat3& s, double*, PointResult& res) {
    const double J = det(k.F_new);
    s = stress_from(p, transpose_times(k.F_new, k.F_new), J);
    if (res.tangent) write_tangent(p, k, s, J, res.tangent);
  }

  /// Axial vector of the skew part of X: (X_32 - X_23, X_13 - X_31, X_21 - X_12).
  static Vec3 axial_of_skew(const Mat3& X) { return {X(2, 1) - X(1, 2), X(0, 2) - X(2, 0), X(1, 0) - X(0, 1)}; }

  /// The tangent of the header comment, 6x6 row-major, order 11, 22, 33, 23, 13, 12, tensor shears.
  static void write_tangent(const Params& p, const PointKinematics& k, const Mat3& sigma_bar, double J, double* T) {
    static constexpr int kA[6] = {0, 1, 2, 1, 0, 0};
    static constexpr int kB[6] = {0, 1, 2, 2, 2, 1};
    const Mat3 U = sym(transpose_times(k.R_new, k.F_new));
    const Mat3 eps = k.dt * k.D_bar;
    const Mat3 A = spin_free_step_for_increment(eps);
    const Mat3 A_inv = inverse(A);
    const Mat3 half_inv = 0.5 * inverse(Mat3::identity() - 0.5 * eps);
    const Mat3 I_plus_A = Mat3::identity() + A;
    const Mat3 M = A_inv * U;
    // Columns of the 3x3 map omega -> axial(skew(A Omega M)), Omega = [omega]_x.
    Mat3 K;
    for (int m = 0; m < 3; ++m) {
      Mat3 Om;
      const int a = (m + 1) % 3, b = (m + 2) % 3;  // [e_m]_x: Om(b, a) = 1, Om(a, b) = -1
      Om(b, a) = 1.0;
      Om(a, b) = -1.0;
      const Vec3 col = axial_of_skew(A * Om * M);
      for (int r = 0; r < 3; ++r) K(r, m) = col[r];
    }
    const Mat3 K_inv = inverse(K);
    for (int j = 0; j < 6; ++j) {
      Mat3 dE;
      dE(kA[j], kB[j]) = 1.0;
      dE(kB[j], kA[j]) = 1.0;
      const Mat3 dA = half_inv * dE * I_plus_A;
      const Mat3 dEM = dA * M;
      const Vec3 rhs = axial_of_skew(dEM);
      Mat3 Om;
      for (int m = 0; m < 3; ++m) {
        double w = 0.0;
        for (int r = 0; r < 3; ++r) w -= K_inv(m, r) * rhs[r];
        const int a = (m + 1) % 3, b = (m + 2) % 3;
        Om(b, a) += w;
        Om(a, b) -= w;
      }
      const Mat3 dU = sym(dEM + A * Om * M);  // symmetric by construction; sym() removes round-off
      const Mat3 dC = dU * U + U * dU;
      const double dJ_J = ddot(A_inv, transpose(dA));  // tr(A^-1 dA)
      Mat3 ds = (p.mu / J) * dC - dJ_J * sigma_bar;
      const double iso = p.lambda * dJ_J / J;
      ds(0, 0) += iso; ds(1, 1) += iso; ds(2, 2) += iso;
      for (int i = 0; i < 6; ++i) T[6 * i + j] = ds(kA[i], kB[i]);
    }
  }

  /// Longitudinal wave speed of the deformed material. From the spatial elasticity tensor of
  /// Bonet & Wood (2008) eq. 6.28-6.29 (lambda' = lambda/J, mu' = (mu - lambda ln J)/J) plus the
  /// initial-stress term of the acoustic tensor, a plane wave along a principal direction n with
  /// squared stretch b_n has rho c^2 = lambda' + 2 mu' + sigma_nn, i.e. (with rho = rho0/J)
  ///   c^2 = [lambda (1 - ln J) + mu (1 + b_n)] / rho0.
  /// Only J is known here, so b_n = J^(2/3) (exact for a spherical deformation); the result is
  /// bounded below by the reference speed sqrt((lambda + 2 mu)/rho0) so that tension never lowers
  /// the estimate. A large deviatoric stretch raises the true speed by mu (b_max - J^(2/3))/rho0,
  /// which is not captured (see docs/materials.md).
  static double wave_speed(const Params& p, const double*, double J) {
    const double c2_ref = p.lambda + 2.0 * p.mu;
    const double c2 = p.lambda * (1.0 - std::log(J)) + p.mu * (1.0 + std::cbrt(J * J));
    return std::sqrt(std::max(c2, c2_ref) / p.density);
  }
};

BALLISTA_REGISTER_MATERIAL(NeoHookean, "compressible neo-Hookean hyperelasticity (Simo-Pister / Bonet-Wood)")

}  // namespace ballista
