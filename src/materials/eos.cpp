#include "materials/eos.hpp"

namespace ballista {

std::vector<ParamSpec> eos_param_specs() {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ParamSpec type{"eos.type", "", "pressure law: linear (hypoelastic, bulk modulus K) or mie_gruneisen", false};
  type.choices = {"linear", "mie_gruneisen"};
  type.default_choice = "linear";
  return {
      type,
      {"eos.sound_speed", "m/s", "Mie-Grüneisen: bulk sound speed c0 (Us = c0 + s up)", false, nan,
       0.0, inf, true, false},
      {"eos.hugoniot_slope", "1", "Mie-Grüneisen: slope s of the Us-up Hugoniot", false, nan, 0.0, inf, false, false},
      {"eos.gruneisen_gamma", "1", "Mie-Grüneisen: Grüneisen coefficient Gamma0 (Gamma rho = Gamma0 rho0)", false,
       nan, 0.0, inf, false, false},
      {"eos.min_pressure", "Pa", "tension cutoff: the pressure never drops below it (cavitation, spall); default none",
       false, nan, -inf, 0.0, false, false},
  };
}

Eos make_eos(const ParamValues& v, double bulk, double density) {
  Eos e;
  e.bulk = bulk;
  e.rho0 = density;
  e.p_min = v.number_or("eos.min_pressure", -std::numeric_limits<double>::infinity());
  const std::string type = v.choice("eos.type", "linear");
  if (type == "linear") return e;
  if (type != "mie_gruneisen") throw ParamError("eos.type", "unknown eos.type '" + type + "'");
  e.kind = Eos::Kind::MieGruneisen;
  for (const char* k : {"eos.sound_speed", "eos.hugoniot_slope", "eos.gruneisen_gamma"})
    if (!v.given(k)) throw ParamError(k, std::string(k) + " is required when eos.type is mie_gruneisen");
  e.c0 = v.at("eos.sound_speed");
  e.s = v.at("eos.hugoniot_slope");
  e.gamma0 = v.at("eos.gruneisen_gamma");
  return e;
}

}  // namespace ballista
