#include "penetration/hydrodynamic.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/input_checks.hpp"

namespace ballista::penetration {

namespace {
void require_lambda(const char* model, double lambda) {
  // eq. 3.3: lambda ranges from 1 (continuous jet) to 2 (fully particulated jet).
  if (!(lambda >= 1 && lambda <= 2))
    throw Error(fmt::format("{}: lambda = {:g} must lie in [1, 2] (1 continuous jet, 2 fully particulated) [1]", model,
                            lambda));
}
}  // namespace

double hydrodynamic_penetration_velocity(double V, double rho_p, double rho_t) {
  require_non_negative("hydrodynamic", "V", V, "m/s");
  require_positive("hydrodynamic", "rho_p", rho_p, "kg/m^3");
  require_positive("hydrodynamic", "rho_t", rho_t, "kg/m^3");
  return V / (1 + std::sqrt(rho_t / rho_p));  // eq. 3.1 solved for U
}

double birkhoff_depth(double L, double rho_p, double rho_t) {
  require_non_negative("birkhoff", "L", L, "m");
  require_positive("birkhoff", "rho_p", rho_p, "kg/m^3");
  require_positive("birkhoff", "rho_t", rho_t, "kg/m^3");
  return L * std::sqrt(rho_p / rho_t);  // eq. 3.2
}

double particulated_jet_velocity(double V, double lambda, double rho_avg, double rho_t) {
  require_non_negative("particulated-jet", "V", V, "m/s");
  require_lambda("particulated-jet", lambda);
  require_positive("particulated-jet", "rho_avg", rho_avg, "kg/m^3");
  require_positive("particulated-jet", "rho_t", rho_t, "kg/m^3");
  return V / (1 + std::sqrt(rho_t / (lambda * rho_avg)));  // eq. 3.3 solved for U
}

double particulated_jet_depth(double L, double lambda, double rho_avg, double rho_t) {
  require_non_negative("particulated-jet", "L", L, "m");
  require_lambda("particulated-jet", lambda);
  require_positive("particulated-jet", "rho_avg", rho_avg, "kg/m^3");
  require_positive("particulated-jet", "rho_t", rho_t, "kg/m^3");
  return L * std::sqrt(lambda * rho_avg / rho_t);  // eq. 3.4
}

}  // namespace ballista::penetration
