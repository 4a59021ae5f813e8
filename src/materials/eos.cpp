#include "materials/eos.hpp"

#include <cmath>

#include "materials/cohesive_limit.hpp"

namespace ballista {

std::vector<ParamSpec> eos_param_specs() {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ParamSpec type{"eos.type", "", "pressure law: linear (hypoelastic, bulk modulus K) or mie_gruneisen", false};
  type.choices = {"linear", "mie_gruneisen"};
  type.default_choice = "linear";
  ParamSpec cap{"eos.tension_cap", "",
                "cohesive_limit: the pressure never drops below the material's cohesive limit, the minimum of the "
                "universal EOS in tension for K0 = rho0 c0^2 and K0' = 4 s - 1 (Mie-Grüneisen only; "
                "materials/cohesive_limit.hpp); none: no cap but eos.min_pressure's",
                false};
  cap.choices = {"none", "cohesive_limit"};
  cap.default_choice = "none";
  return {
      type,
      cap,
      {"eos.sound_speed", "m/s", "Mie-Grüneisen: bulk sound speed c0 (Us = c0 + s up)", false, nan,
       0.0, inf, true, false},
      {"eos.hugoniot_slope", "1", "Mie-Grüneisen: slope s of the Us-up Hugoniot", false, nan, 0.0, inf, false, false},
      {"eos.gruneisen_gamma", "1", "Mie-Grüneisen: Grüneisen coefficient Gamma0 (Gamma rho = Gamma0 rho0)", false,
       nan, 0.0, inf, false, false},
      {"eos.min_pressure", "Pa", "tension cutoff: the pressure never drops below it (cavitation, spall); default none",
       false, nan, -inf, 0.0, false, false},
      {"eos.max_particle_velocity", "m/s",
       "Mie-Grüneisen: particle velocity where the Us-up line's data end; beyond that shock's compression "
       "the Hugoniot continues along its tangent instead of to the line's pole; default none",
       false, nan, 0.0, inf, true, false},
  };
}

double eos_hugoniot_tangent(const Eos& e, double eta) { return e.p_fit + e.dp_fit * (eta - e.eta_fit); }

double eos_bulk_modulus_tangent(const Eos& e, double J, double energy) {
  return eos_modulus_with_slope(e, J, energy, e.dp_fit);
}

Eos make_eos(const ParamValues& v, double bulk, double density) {
  Eos e;
  e.bulk = bulk;
  e.rho0 = density;
  e.p_min = v.number_or("eos.min_pressure", -std::numeric_limits<double>::infinity());
  const std::string type = v.choice("eos.type", "linear");
  const bool cohesive_cap = v.choice("eos.tension_cap", "none") == "cohesive_limit";
  if (cohesive_cap && v.given("eos.min_pressure"))
    throw ParamError("eos.tension_cap", "eos.tension_cap and eos.min_pressure both set the tension cutoff: give one");
  if (type == "linear") {
    if (v.given("eos.max_particle_velocity"))
      throw ParamError("eos.max_particle_velocity", "eos.max_particle_velocity needs eos.type mie_gruneisen");
    if (cohesive_cap)
      throw ParamError("eos.tension_cap",
                       "eos.tension_cap: cohesive_limit needs eos.type mie_gruneisen (the limit is built from its c0 "
                       "and s); a linear EOS takes eos.min_pressure");
    return e;
  }
  if (type != "mie_gruneisen") throw ParamError("eos.type", "unknown eos.type '" + type + "'");
  e.kind = Eos::Kind::MieGruneisen;
  for (const char* k : {"eos.sound_speed", "eos.hugoniot_slope", "eos.gruneisen_gamma"})
    if (!v.given(k)) throw ParamError(k, std::string(k) + " is required when eos.type is mie_gruneisen");
  e.c0 = v.at("eos.sound_speed");
  e.s = v.at("eos.hugoniot_slope");
  e.gamma0 = v.at("eos.gruneisen_gamma");
  if (v.given("eos.max_particle_velocity")) {
    // The Hugoniot's compression at that particle velocity, eta = up / Us (Meyers 1994 §4.3),
    // and the line's pressure and slope there (eos.hpp): the tangent's anchor.
    const double u = v.at("eos.max_particle_velocity");
    const double eta = u / (e.c0 + e.s * u);
    e.p_fit = eos_line_pressure(e, eta);
    e.dp_fit = eos_line_slope(e, eta);
    e.eta_fit = eta;
  }
  if (cohesive_cap) {
    e.p_min = mie_gruneisen_cohesive_limit(e);
    if (!std::isfinite(e.p_min))
      throw ParamError("eos.tension_cap", "eos.tension_cap: cohesive_limit needs eos.hugoniot_slope > 1/2 (K0' = 4 s - 1 "
                                          "> 1: below it the universal EOS has no minimum in tension)");
  }
  return e;
}

}  // namespace ballista
