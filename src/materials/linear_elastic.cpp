// Hypoelastic isotropic linear elasticity in the unrotated frame:
//   sigma_bar_{n+1} = sigma_bar_n + dt (lambda tr(D_bar) I + 2 G D_bar)
// (thesis seed 000 §2.3, eq. 2.6: the rate of deformation is rotated by R of F = R U, which makes
// the update objective; for small elastic strain D_bar approximates the Hencky strain rate).
#include <cmath>

#include "materials/elastic_constants.hpp"
#include "materials/material_adapter.hpp"

namespace ballista {

struct LinearElastic {
  static constexpr const char* kName = "linear_elastic";
  struct Params {
    double density = 0;  ///< kg/m^3
    double bulk = 0;     ///< K, Pa
    double shear = 0;    ///< G, Pa
  };
  static std::vector<ParamSpec> param_specs() { return elastic_param_specs(); }
  static Params make(const ParamValues& v) {
    const ElasticConstants e = elastic_constants_from(v);
    return {v.at("density"), e.bulk, e.shear};
  }
  // Verification hooks (MaterialFactory): steel-like example; A1 reduction is the model itself.
  static ParamValues example_params() { return {{"density", 7850.0}, {"bulk_modulus", 160e9}, {"shear_modulus", 79e9}}; }
  static ParamValues reduce_to_elastic(double rho, double K, double G) {
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}};
  }

  static std::vector<StateFieldSpec> state_fields() { return {}; }
  static void update(const Params& p, const PointKinematics& k, Mat3& s, double*, PointResult&) {
    const double lam = p.bulk - 2.0 * p.shear / 3.0;
    const double trD = trace(k.D_bar);
    s += k.dt * (2.0 * p.shear) * k.D_bar;
    const double iso = k.dt * lam * trD;
    s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
  }
  /// Dilatational wave speed sqrt((K + 4G/3)/rho), rho = rho0/J.
  static double wave_speed(const Params& p, const double*, double J) {
    return std::sqrt((p.bulk + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

BALLISTA_REGISTER_MATERIAL(LinearElastic, "hypoelastic isotropic linear elasticity, unrotated frame")

}  // namespace ballista
