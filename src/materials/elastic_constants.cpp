#include "materials/elastic_constants.hpp"

#include <cmath>

namespace ballista {

std::vector<ParamSpec> elastic_param_specs() {
  const double inf = std::numeric_limits<double>::infinity();
  return {
      {"density", "kg/m^3", "reference mass density rho0", true, 0.0, 0.0, inf, true, false},
      {"youngs_modulus", "Pa", "Young's modulus E (give E and nu, or K and G)", false, NAN, 0.0, inf, true, false},
      {"poisson_ratio", "1", "Poisson's ratio nu", false, NAN, -1.0, 0.5, true, true},
      {"bulk_modulus", "Pa", "bulk modulus K (alternative to E, nu)", false, NAN, 0.0, inf, true, false},
      {"shear_modulus", "Pa", "shear modulus G (alternative to E, nu)", false, NAN, 0.0, inf, true, false},
  };
}

ElasticConstants elastic_constants_from(const ParamValues& v) {
  auto given = [&](const char* k) {
    auto it = v.find(k);
    return it != v.end() && !std::isnan(it->second);
  };
  const bool e_nu = given("youngs_modulus") || given("poisson_ratio");
  const bool k_g = given("bulk_modulus") || given("shear_modulus");
  if (e_nu && k_g)
    throw ParamError(given("bulk_modulus") ? "bulk_modulus" : "shear_modulus",
                     "give either youngs_modulus and poisson_ratio, or bulk_modulus and shear_modulus, not both");
  if (e_nu) {
    if (!given("youngs_modulus")) throw ParamError("youngs_modulus", "poisson_ratio needs youngs_modulus");
    if (!given("poisson_ratio")) throw ParamError("poisson_ratio", "youngs_modulus needs poisson_ratio");
    const double E = v.at("youngs_modulus"), nu = v.at("poisson_ratio");
    return {E / (3.0 * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
  }
  if (k_g) {
    if (!given("bulk_modulus")) throw ParamError("bulk_modulus", "shear_modulus needs bulk_modulus");
    if (!given("shear_modulus")) throw ParamError("shear_modulus", "bulk_modulus needs shear_modulus");
    return {v.at("bulk_modulus"), v.at("shear_modulus")};
  }
  throw ParamError("youngs_modulus", "elastic constants missing: give youngs_modulus and poisson_ratio, or "
                                     "bulk_modulus and shear_modulus");
}

}  // namespace ballista
