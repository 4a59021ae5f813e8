#pragma once
// Steady interface balance shared by the strength-corrected Bernoulli models: Eichelberger
// (thesis seed 000 eq. 3.6), Alekseevskii-Tate (eq. 3.9, k = rho_p) and Grove (eq. 3.11 = 3.12,
// k = rho_d (1 + phi)):
//     k (V - U)^2 = rho_t U^2 + 2 sigma,     sigma = R - Y (eq. 3.7).
// SI units: densities kg/m^3, velocities m/s, strengths Pa.
#include <string>

namespace ballista::penetration {

/// Which branch of the balance holds at the given impact velocity.
enum class InterfaceRegime {
  kEroding,        ///< 0 < U < V: the penetrator erodes while the target is penetrated
  kNoPenetration,  ///< k V^2 <= 2 sigma: the target is too strong, U = 0
  kRigid,          ///< rho_t V^2 <= -2 sigma: the penetrator is too strong to erode, U = V
};

struct InterfaceSolution {
  double U = 0;  ///< penetration velocity [m/s]
  InterfaceRegime regime = InterfaceRegime::kEroding;
};

std::string to_string(InterfaceRegime r);

/// Root U in [0, V] of k (V - U)^2 = rho_t U^2 + 2 sigma. The closed form of the quadratic,
/// written without cancellation (also for k = rho_t):
///     U = (V^2 - A) / (V + sqrt(mu^2 V^2 + (1 - mu^2) A)),  mu^2 = rho_t / k,  A = 2 sigma / k.
/// k [kg/m^3] > 0, rho_t [kg/m^3] > 0, V [m/s] >= 0, sigma [Pa] any sign.
InterfaceSolution solve_interface(double k, double rho_t, double sigma, double V);

}  // namespace ballista::penetration
