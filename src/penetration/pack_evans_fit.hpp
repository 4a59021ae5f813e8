#pragma once
// Extraction of the Pack-Evans coefficients from a measured (or simulated) depth, thesis seed 000
// §6.4, eq. 6.15-6.16. SI units: m, kg/m^3, Pa, m/s.
#include "penetration/strength_models.hpp"

namespace ballista::penetration {

struct PackEvansObservation {
  double P = 0;                                             ///< observed depth [m]
  double r = 0;                                             ///< channel radius [m]
  double L = 0;                                             ///< jet/rod length [m]
  double lambda = 1;                                        ///< particulation factor [1] (given when extracting alpha)
  double rho_p = 0;                                         ///< penetrator density [kg/m^3]
  double rho_t = 0;                                         ///< target density [kg/m^3]
  double sigma_y = 0;                                       ///< target yield strength [Pa] (alpha only)
  double V = 0;                                             ///< impact velocity [m/s] (alpha only)
  PackEvansForm form = PackEvansForm::kPenaltyOutsideRoot;  ///< §6.4 uses the penalty outside the root
};

/// Dimensionless penalty x = alpha sigma_y / (rho_p V^2) that makes pack_evans_depth return P:
///   outside root (eq. 6.15): x = 1 - sqrt(rho_t/(lambda rho_p)) (P - r)/L,
///   inside root (inverse of eq. 3.5 as printed): x = 1 - rho_t/(lambda rho_p) ((P - r)/L)^2.
double pack_evans_extract_penalty(const PackEvansObservation& obs);

/// Alpha of eq. 6.15: x rho_p V^2 / sigma_y.
double pack_evans_extract_alpha(const PackEvansObservation& obs);

/// Lambda that makes pack_evans_depth return P for a given penalty x:
///   outside root (eq. 6.16): lambda = rho_t/rho_p [(P - r) / (L (1 - x))]^2,
///   inside root (inverse of eq. 3.5): lambda = rho_t/rho_p ((P - r)/L)^2 / (1 - x).
double pack_evans_extract_lambda(const PackEvansObservation& obs, double penalty);

}  // namespace ballista::penetration
