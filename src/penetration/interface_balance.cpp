#include "penetration/interface_balance.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"

namespace ballista::penetration {

std::string to_string(InterfaceRegime r) {
  switch (r) {
    case InterfaceRegime::kEroding:
      return "eroding";
    case InterfaceRegime::kNoPenetration:
      return "no_penetration";
    case InterfaceRegime::kRigid:
      return "rigid";
  }
  return "unknown";
}

void require_finite(const char* model, const char* name, double x, const char* unit) {
  if (!std::isfinite(x)) throw Error(fmt::format("{}: {} = {} must be a finite number [{}]", model, name, x, unit));
}

void require_positive(const char* model, const char* name, double x, const char* unit) {
  if (!(std::isfinite(x) && x > 0)) throw Error(fmt::format("{}: {} = {:g} must be > 0 [{}]", model, name, x, unit));
}

void require_non_negative(const char* model, const char* name, double x, const char* unit) {
  if (!(std::isfinite(x) && x >= 0)) throw Error(fmt::format("{}: {} = {:g} must be >= 0 [{}]", model, name, x, unit));
}

InterfaceSolution solve_interface(double k, double rho_t, double sigma, double V) {
  require_positive("interface balance", "penetrator density", k, "kg/m^3");
  require_positive("interface balance", "rho_t", rho_t, "kg/m^3");
  require_finite("interface balance", "sigma", sigma, "Pa");
  require_non_negative("interface balance", "V", V, "m/s");
  const double mu2 = rho_t / k, A = 2 * sigma / k;
  // U >= 0 needs k V^2 >= 2 sigma (eq. 3.6 at U = 0); U <= V needs rho_t V^2 >= -2 sigma (at U = V).
  if (V * V <= A) return {0.0, InterfaceRegime::kNoPenetration};
  if (mu2 * V * V <= -A) return {V, InterfaceRegime::kRigid};
  // (V - U)^2 - mu^2 U^2 = A  <=>  (1 - mu^2) U^2 - 2 V U + V^2 - A = 0; the root below V,
  // rationalised: (V - s)(V + s) = (1 - mu^2)(V^2 - A) with s the square root below.
  const double s = std::sqrt(mu2 * V * V + (1 - mu2) * A);
  return {(V * V - A) / (V + s), InterfaceRegime::kEroding};
}

}  // namespace ballista::penetration
