// Water: a strengthless, inviscid fluid. The stress is a pure pressure, sigma = -p I, from the
// equation of state of materials/eos.hpp (Mie-Grüneisen with a linear Us-up Hugoniot by default,
// or eos.type linear for an acoustic fluid with K = rho0 c0^2); no deviatoric stress, no
// viscosity. The pressure depends on J = det F and the energy E only, so the update is exactly
// objective and exactly path-independent along isentropes up to the EOS's trapezoidal energy rule.
//
// Default constants (all overridable in the deck's eos: map):
//   density 998.2 kg/m^3: water at 20 °C and 0.1 MPa (IAPWS-95, W. Wagner & A. Pruß,
//     J. Phys. Chem. Ref. Data 31 (2002) 387: 998.21 kg/m^3).
//   eos.sound_speed c0 = 1647 m/s, eos.hugoniot_slope s = 1.921, eos.gruneisen_gamma = 0.35: the
//     Us-up fit for water of D.J. Steinberg, "Equation of state and strength properties of selected
//     materials", LLNL UCRL-MA-106439 (1996), whose quadratic coefficient S2 = -0.096 is dropped here
//     (linear Hugoniot; it changes Us by < 1 % for up <= 1 km/s). The fit targets shock states: its
//     c0 exceeds the acoustic sound speed of water (1482 m/s at 20 °C) by 11 %; set
//     eos.sound_speed: 1482 for low-amplitude acoustics.
//   eos.min_pressure = -1e5 Pa: cavitation. The reference state (p = 0) is taken at one atmosphere;
//     real water, which holds cavitation nuclei, cannot sustain an absolute pressure much below its
//     vapour pressure (2.3 kPa at 20 °C), i.e. about -1e5 Pa gauge (C.E. Brennen, Cavitation and
//     Bubble Dynamics, Oxford 1995, §1.2-1.4; R.H. Cole, Underwater Explosions, Princeton 1948 on
//     bulk cavitation). The cutoff holds p there while the fluid expands (no tension wave beyond).
//
// Algorithmic tangent (PointResult::tangent, d sigma_bar_{n+1}/d eps, eps = D_bar dt): pressure only,
// sigma = -p I, so the shear rows are zero and rows 11, 22, 33 each equal -dp/d eps, the derivative of
// the closed-form eos_update (Hugoniot term and energy coupling, J_{n+1} = J_n det(I + eps) for a
// spin-free increment; zero while the cavitation cutoff holds p = p_min): j2_compose_eos of
// j2_return.hpp with a zero deviatoric tangent.
#include <cmath>

#include "materials/eos.hpp"
#include "materials/j2_return.hpp"
#include "materials/material_adapter.hpp"

namespace ballista {

struct Water {
  static constexpr const char* kName = "water";
  struct Params {
    double density = 0;  ///< rho0, kg/m^3
    Eos eos;
  };

  static std::vector<ParamSpec> param_specs() {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<ParamSpec> s{{"density", "kg/m^3", "reference mass density rho0", false, 998.2, 0.0, inf, true, false}};
    for (ParamSpec e : eos_param_specs()) {
      if (e.name == "eos.type") e.default_choice = "mie_gruneisen";
      if (e.name == "eos.sound_speed") e.default_value = 1647.0;
      if (e.name == "eos.hugoniot_slope") e.default_value = 1.921;
      if (e.name == "eos.gruneisen_gamma") e.default_value = 0.35;
      if (e.name == "eos.min_pressure") e.default_value = -1.0e5;
      if (e.name == "eos.sound_speed") e.description = "bulk sound speed c0 (Us = c0 + s up; linear: K = rho0 c0^2)";
      s.push_back(std::move(e));
    }
    return s;
  }

  static Params make(const ParamValues& given) {
    // Values absent from `given` (a programmatic caller; the deck fills every default) take the
    // defaults above.
    const ParamValues v = with_defaults(given, param_specs());
    const double rho = v.at("density");
    const double c0 = v.at("eos.sound_speed");
    if (!(rho > 0.0)) throw ParamError("density", "density must be > 0");
    if (!(c0 > 0.0)) throw ParamError("eos.sound_speed", "eos.sound_speed must be > 0");
    return {rho, make_eos(v, rho * c0 * c0, rho)};
  }

  // Verification hooks: the default water (objectivity checks). No reduction to elasticity or J2:
  // a fluid has no shear stiffness.
  static ParamValues example_params() {
    ParamValues v{{"density", 998.2},
                  {"eos.sound_speed", 1647.0},
                  {"eos.hugoniot_slope", 1.921},
                  {"eos.gruneisen_gamma", 0.35},
                  {"eos.min_pressure", -1.0e5}};
    v.choices["eos.type"] = "mie_gruneisen";
    return v;
  }

  static std::vector<StateFieldSpec> state_fields() { return {eos_state_field()}; }

  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* state, PointResult& res) {
    const double p_old = -trace(s) / 3.0;
    // No deviator (s_n = s_{n+1} = 0), hence no deviatoric work: p from eos_update, sigma = -p I.
    const Mat3 zero;
    s = j2_compose_eos(p.eos, k, k.dt * k.D_bar, p_old, zero, zero, state[0], true, DevTangent{}, res);
  }

  /// Bulk sound speed sqrt(K_s / rho), K_s the isentropic bulk modulus, rho = rho0 / J.
  /// Cavitated (expanded, its Mie-Grüneisen pressure at or below the cutoff eos.min_pressure) the
  /// pressure no longer depends on J: the parted fluid has no stiffness of its own, while the
  /// tension branch's sqrt(K J / rho0) grows without bound with J (a spray point expanded
  /// 1,240-fold gave 41 km/s and held a perforation run's step 3x small). There the estimate is
  /// the speed at rest, the speed the point has again when it closes to J = 1. Water's estimate
  /// only: the solids' Mie-Grüneisen speed (eos_bulk_modulus) is left as it was, and with it their runs.
  static double wave_speed(const Params& p, const double* state, double J) {
    const bool cavitated = p.eos.kind == Eos::Kind::MieGruneisen && J > 1.0 &&
                           eos_mg_pressure(p.eos, J, state[0]) <= p.eos.p_min;
    const double j = cavitated ? 1.0 : J;
    return std::sqrt(eos_bulk_modulus(p.eos, j, state[0]) * j / p.density);
  }
};

BALLISTA_REGISTER_MATERIAL(Water, "water: strengthless inviscid fluid, Mie-Grüneisen pressure with cavitation cutoff")

}  // namespace ballista
