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
#include <cmath>

#include "materials/elastic_constants.hpp"
#include "materials/eos.hpp"
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
  static ParamValues example_params() { return {{"density", 7850.0}, {"bulk_modulus", 160e9}, {"shear_modulus", 79e9}}; }
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

  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* state, PointResult&) {
    if (p.eos.kind == Eos::Kind::Linear) {
      const double lam = p.bulk - 2.0 * p.shear / 3.0;
      const double trD = trace(k.D_bar);
      s += k.dt * (2.0 * p.shear) * k.D_bar;
      const double iso = k.dt * lam * trD;
      s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
      return;
    }
    const double p_old = -trace(s) / 3.0;
    const Mat3 dev_old = deviator(s);
    const Mat3 dev_new = dev_old + k.dt * (2.0 * p.shear) * deviator(k.D_bar);
    // Deviatoric work per reference volume, J_mid s_mid : D_bar dt (trapezoidal, as eos_update).
    const double dev_work = 0.5 * (k.J_old + k.J_new) * 0.5 * ddot(dev_old + dev_new, k.D_bar) * k.dt;
    const double p_new = eos_update(p.eos, k, p_old, state[0], dev_work);
    s = dev_new;
    s(0, 0) -= p_new; s(1, 1) -= p_new; s(2, 2) -= p_new;
  }

  /// Dilatational wave speed sqrt((K + 4G/3)/rho), rho = rho0/J; with Mie-Grüneisen K is the
  /// isentropic bulk modulus eos_bulk_modulus(J, E).
  static double wave_speed(const Params& p, const double* state, double J) {
    const double K = p.eos.kind == Eos::Kind::Linear ? p.bulk : eos_bulk_modulus(p.eos, J, state[0]);
    return std::sqrt((K + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

BALLISTA_REGISTER_MATERIAL(LinearElastic, "hypoelastic isotropic linear elasticity (optionally with a Mie-Grüneisen EOS), unrotated frame")

}  // namespace ballista
