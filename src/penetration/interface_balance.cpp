#include "penetration/interface_balance.hpp"

#include <cmath>

#include "penetration/input_checks.hpp"

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

InterfaceSolution solve_interface(double k, double rho_t, double sigma, double V) {
  require_inputs("interface balance", {positive("penetrator density", k, "kg/m^3"), positive("rho_t", rho_t, "kg/m^3"),
                                       finite("sigma", sigma, "Pa"), non_negative("V", V, "m/s")});
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
