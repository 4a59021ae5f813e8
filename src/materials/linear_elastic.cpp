// Hypoelastic isotropic linear elasticity in the unrotated frame:
//   sigma_bar_{n+1} = sigma_bar_n + dt (lambda tr(D_bar) I + 2 G D_bar)
// (thesis seed 000 §2.3, eq. 2.6: the rate of deformation is rotated by R of F = R U, which makes
// the update objective; for small elastic strain D_bar approximates the Hencky strain rate).
//
// With an equation of state (eos.type mie_gruneisen, materials/eos.hpp) the same deviatoric law
// is composed with the EOS pressure: sigma_bar = s - p I,
//   s_{n+1} = s_n + 2 G dev(D_bar) dt,
//   p_{n+1} = eos_update(p_n, J_n -> J_{n+1}, E, W_dev),  W_dev = J_mid s_mid : D_bar dt,
// so the deviatoric elastic work enters the energy E that the Grüneisen term sees. eos.type linear
// (the default) is the plain update above, unchanged (its pressure part is p_n - K tr(D_bar) dt).
//
// Algorithmic tangent (PointResult::tangent, d sigma_bar_{n+1}/d eps with eps = D_bar dt): the
// deviatoric part is 2G I_dev; the pressure part is -K 1 (x) 1 for eos.type linear and, for
// Mie-Grüneisen, the derivative of the closed-form eos_update including the energy coupling and the
// deviatoric work, with J_{n+1} = J_n det(I + eps) (a spin-free increment): j2_compose_eos of
// j2_return.hpp with the elastic deviatoric tangent (zero slope while the tension cutoff holds).
#include <cmath>

#include "materials/elastic_constants.hpp"
#include "materials/eos.hpp"
#include "materials/j2_return.hpp"
#include "materials/material_adapter.hpp"

namespace ballista {

struct LinearElastic {
  static constexpr const char* kName = "linear_elastic";
  struct Params {
    double density = 0;  ///< kg/m^3
    double bulk = 0;     ///< K, Pa
    double shear = 0;    ///< G, Pa
    Eos eos;             ///< pressure law (linear: K above)
  };
  static std::vector<ParamSpec> param_specs() {
    std::vector<ParamSpec> s = elastic_param_specs();
    for (auto& e : eos_param_specs()) s.push_back(std::move(e));
    return s;
  }
  static Params make(const ParamValues& v) {
    const ElasticConstants e = elastic_constants_from(v);
    const double rho = v.at("density");
    return {rho, e.bulk, e.shear, make_eos(v, e.bulk, rho)};
  }
  // Verification hooks (MaterialFactory): steel-like example; A1 reduction is the model itself.
  static ParamValues example_params() {
    return {{"density", 7850.0}, {"bulk_modulus", 160e9}, {"shear_modulus", 79e9}};
  }
  static ParamValues reduce_to_elastic(double rho, double K, double G) {
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}};
  }

  /// Listed by `ballista info`: none with eos.type linear; a Mie-Grüneisen instance adds the EOS
  /// energy (state_fields(params)).
  static std::vector<StateFieldSpec> state_fields() { return {}; }
  static std::vector<StateFieldSpec> state_fields(const Params& p) {
    if (p.eos.kind == Eos::Kind::Linear) return {};
    return {eos_state_field()};
  }

  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* state, PointResult& res) {
    if (p.eos.kind == Eos::Kind::Linear) {
      const double lam = p.bulk - 2.0 * p.shear / 3.0;
      const double trD = trace(k.D_bar);
      s += k.dt * (2.0 * p.shear) * k.D_bar;
      const double iso = k.dt * lam * trD;
      s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
      // d sigma = 2G dev(d eps) + K tr(d eps) I (the eos.min_pressure cutoff does not apply here).
      if (res.tangent) j2_write_tangent(res.tangent, elastic_tangent(p.shear), (-p.bulk) * Mat3::identity());
      return;
    }
    const double p_old = -trace(s) / 3.0;
    const Mat3 eps = k.dt * k.D_bar;
    const Mat3 dev_old = deviator(s);
    const Mat3 dev_new = dev_old + (2.0 * p.shear) * deviator(eps);
    // Pressure from eos_update with the deviatoric work J_mid s_mid : eps (trapezoidal, as
    // eos_update), sigma = s - p I, and the tangent if requested.
    s = j2_compose_eos(p.eos, k, eps, p_old, dev_old, dev_new, state[0], true, elastic_tangent(p.shear), res);
  }

  /// Dilatational wave speed sqrt((K + 4G/3)/rho), rho = rho0/J; with Mie-Grüneisen K is the
  /// isentropic bulk modulus eos_bulk_modulus(J, E).
  static double wave_speed(const Params& p, const double* state, double J) {
    const double K = p.eos.kind == Eos::Kind::Linear ? p.bulk : eos_bulk_modulus(p.eos, J, state[0]);
    return std::sqrt((K + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

BALLISTA_REGISTER_MATERIAL(LinearElastic,
                           "hypoelastic isotropic linear elasticity (optionally with a Mie-Grüneisen EOS), "
                           "unrotated frame")

}  // namespace ballista
