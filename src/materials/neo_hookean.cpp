// Compressible neo-Hookean hyperelasticity (Simo & Pister 1984; Bonet & Wood, Nonlinear Continuum
// Mechanics for Finite Element Analysis, 2nd ed. 2008, §6.4.3, eq. 6.28):
//   W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2
//   sigma = [lambda ln J I + mu (F F^T - I)] / J              (verification CATALOGUE B1)
// Being hyperelastic, the stress is a function of F_new alone: the kernel writes the unrotated
// stress directly, sigma_bar = R^T sigma R = [lambda ln J I + mu (C - I)] / J with C = F^T F
// (R^T F F^T R = U U = C), and ignores D_bar and the stress at t_n. Objectivity is exact.
// lambda = K - 2G/3, mu = G (small-strain limit is isotropic linear elasticity with K, G).
#include <algorithm>
#include <cmath>

#include "materials/elastic_constants.hpp"
#include "materials/material_adapter.hpp"

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

  static void update(const Params& p, const PointKinematics& k, Mat3& s, double*, PointResult&) {
    s = stress_from(p, transpose_times(k.F_new, k.F_new), det(k.F_new));
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
