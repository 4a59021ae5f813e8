// von Mises (J2) plasticity with linear isotropic hardening, hypoelastic in the unrotated frame.
//
// Elastic predictor as linear_elastic (thesis seed 000 §2.3, eq. 2.6: D_bar = R^T D R with R from
// F = R U; D_bar approximates the Hencky strain rate for small elastic strain):
//   sigma_trial = sigma_bar_n + dt (lambda tr(D_bar) I + 2 G D_bar)
// Plastic corrector: radial return of Simo & Hughes, Computational Inelasticity (1998), §3.3.1,
// Box 3.1, with yield function f = sqrt(3/2)|s| - (sigma_y0 + H eps_p) (see j2_return.hpp).
// Pressure is purely elastic (K tr(D_bar) dt per step); plastic flow is deviatoric.
//
// H is the plastic (not the tangent) modulus: sigma_y(eps_p) = sigma_y0 + H eps_p, so in uniaxial
// stress the elastic-plastic tangent is E H / (E + H). The "linear hardening modulus 100 MPa" of
// the Taylor-anvil benchmark (verification CATALOGUE B6) is this H.
#include <cmath>

#include "materials/elastic_constants.hpp"
#include "materials/j2_return.hpp"
#include "materials/material_adapter.hpp"

namespace ballista {

struct J2Plasticity {
  static constexpr const char* kName = "j2_plasticity";
  struct Params {
    double density = 0;     ///< rho0, kg/m^3
    double bulk = 0;        ///< K, Pa
    double shear = 0;       ///< G, Pa
    double yield = 0;       ///< initial yield stress in uniaxial tension sigma_y0 = sqrt(3) tau_y, Pa
    double hardening = 0;   ///< plastic modulus H = d sigma_y / d eps_p, Pa
  };

  static std::vector<ParamSpec> param_specs() {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<ParamSpec> s = elastic_param_specs();
    s.push_back({"yield_stress", "Pa",
                 "initial yield stress sigma_y0 in uniaxial tension (= sqrt(3) x yield in shear)", true,
                 0.0, 0.0, inf, true, false});
    s.push_back({"hardening_modulus", "Pa",
                 "linear isotropic hardening (plastic) modulus H: sigma_y = sigma_y0 + H eps_p", false,
                 0.0, 0.0, inf, false, false});
    return s;
  }

  static Params make(const ParamValues& v) {
    const ElasticConstants e = elastic_constants_from(v);
    Params p;
    p.density = v.at("density");
    p.bulk = e.bulk;
    p.shear = e.shear;
    auto it = v.find("yield_stress");
    if (it == v.end() || std::isnan(it->second)) throw ParamError("yield_stress", "yield_stress is required");
    p.yield = it->second;
    if (!(p.yield > 0.0)) throw ParamError("yield_stress", "yield_stress must be > 0");
    it = v.find("hardening_modulus");
    p.hardening = (it == v.end() || std::isnan(it->second)) ? 0.0 : it->second;
    if (!(p.hardening >= 0.0)) throw ParamError("hardening_modulus", "hardening_modulus must be >= 0");
    return p;
  }

  // Verification hooks (MaterialFactory).
  static ParamValues example_params() {
    return {{"density", 8930.0}, {"youngs_modulus", 117e9}, {"poisson_ratio", 0.35}, {"yield_stress", 400e6},
            {"hardening_modulus", 100e6}};
  }
  /// Elastic reduction: a yield stress no A1 path can reach.
  static ParamValues reduce_to_elastic(double rho, double K, double G) {
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}, {"yield_stress", 1e30}};
  }
  static ParamValues reduce_to_j2(double rho, double K, double G, double sy, double h_iso, double h_kin) {
    if (h_kin != 0.0) return {};  // no kinematic hardening yet
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}, {"yield_stress", sy}, {"hardening_modulus", h_iso}};
  }

  static std::vector<StateFieldSpec> state_fields() { return {{"eqps", "1", 0.0}}; }

  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* state, PointResult& res) {
    // Elastic predictor (hypoelastic, unrotated frame).
    const double lam = p.bulk - 2.0 * p.shear / 3.0;
    s += k.dt * (2.0 * p.shear) * k.D_bar;
    const double iso = k.dt * lam * trace(k.D_bar);
    s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
    // Plastic corrector; the stress is in the unrotated frame, J2 is isotropic so the frame does
    // not matter for the return itself.
    const J2Return r = j2_radial_return(s, state[0], p.shear, p.yield, p.hardening);
    res.plastic_work_density = r.plastic_work;
  }

  /// Elastic dilatational wave speed sqrt((K + 4G/3)/rho), rho = rho0/J (plastic flow only slows
  /// the deviatoric part, so the elastic speed bounds it).
  static double wave_speed(const Params& p, const double*, double J) {
    return std::sqrt((p.bulk + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

BALLISTA_REGISTER_MATERIAL(J2Plasticity,
                           "von Mises plasticity, linear isotropic hardening, radial return, unrotated frame")

}  // namespace ballista
