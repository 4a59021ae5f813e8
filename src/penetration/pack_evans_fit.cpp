#include "penetration/pack_evans_fit.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/input_checks.hpp"

namespace ballista::penetration {

namespace {
void validate_common(const PackEvansObservation& o) {
  require_inputs("pack-evans-fit", {non_negative("P", o.P, "m"), non_negative("r", o.r, "m"), positive("L", o.L, "m"),
                                    positive("rho_p", o.rho_p, "kg/m^3"), positive("rho_t", o.rho_t, "kg/m^3")});
  if (o.P < o.r)
    throw Error(fmt::format("pack-evans-fit: P = {:g} m must be >= r = {:g} m (eq. 3.5: P - r is the primary depth)",
                            o.P, o.r));
}
}  // namespace

double pack_evans_extract_penalty(const PackEvansObservation& o) {
  validate_common(o);
  require_positive("pack-evans-fit", "lambda", o.lambda, "1");
  const double q = (o.P - o.r) / o.L, ratio = o.rho_t / (o.lambda * o.rho_p);
  if (o.form == PackEvansForm::kPenaltyOutsideRoot) return 1 - std::sqrt(ratio) * q;  // eq. 6.15 (lambda = 1 there)
  return 1 - ratio * q * q;                                                           // eq. 3.5 solved for x
}

double pack_evans_extract_alpha(const PackEvansObservation& o) {
  require_positive("pack-evans-fit", "sigma_y", o.sigma_y, "Pa");
  require_positive("pack-evans-fit", "V", o.V, "m/s");
  return pack_evans_extract_penalty(o) * o.rho_p * o.V * o.V / o.sigma_y;  // eq. 6.15
}

double pack_evans_extract_lambda(const PackEvansObservation& o, double x) {
  validate_common(o);
  require_finite("pack-evans-fit", "penalty", x, "1");
  if (!(x < 1)) throw Error(fmt::format("pack-evans-fit: penalty = {:g} must be < 1 (eq. 6.16 divides by 1 - x)", x));
  const double q = (o.P - o.r) / o.L;
  if (o.form == PackEvansForm::kPenaltyOutsideRoot) return o.rho_t / o.rho_p * std::pow(q / (1 - x), 2);  // eq. 6.16
  return o.rho_t / o.rho_p * q * q / (1 - x);  // eq. 3.5 solved for lambda
}

}  // namespace ballista::penetration
