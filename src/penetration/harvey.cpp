#include "penetration/harvey.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/input_checks.hpp"

namespace ballista::penetration {

HarveyResult harvey_depth(const HarveyInput& in) {
  require_inputs("harvey", {positive("P_ref", in.P_ref, "m"), non_negative("alpha0", in.alpha0, "1/Pa"),
                            non_negative("sigma_ucs", in.sigma_ucs, "Pa"), non_negative("P_c", in.P_c, "Pa"),
                            non_negative("P_p", in.P_p, "Pa")});
  if (!(in.porosity >= 0 && in.porosity <= 1))
    throw Error(fmt::format("harvey: porosity = {:g} must lie in [0, 1] (a fraction; eq. 3.17 takes percent) [1]",
                            in.porosity));
  // Field units inside: psi and percent.
  const double ucs = in.sigma_ucs / kPascalPerPsi, Pc = in.P_c / kPascalPerPsi, Pp = in.P_p / kPascalPerPsi;
  const double alpha0 = in.alpha0 * kPascalPerPsi;  // [1/psi]
  const double phi_percent = 100 * in.porosity;
  const double a = 0.0967 * std::pow(phi_percent, 0.428);  // eq. 3.17
  const double b = ucs < 30000 ? 0.7336 - 1.813e-5 * ucs   // eq. 3.18, sigma_ucs < 30000 psi
                               : 3.33 * std::exp(-9.55e-5 * ucs);
  const double P_eff = Pc - a * Pp;                                   // eq. 3.16 (see header)
  const double F_BI = ucs + b * P_eff;                                // eq. 3.15 [psi]
  const double depth = in.P_ref * std::exp(alpha0 * (10000 - F_BI));  // eq. 3.14
  return {depth, F_BI * kPascalPerPsi, P_eff * kPascalPerPsi, a, b};
}

}  // namespace ballista::penetration
