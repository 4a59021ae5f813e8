#pragma once
// Orphal & Anderson (Int. J. Impact Eng. 33 (2006) 546-554) linear law U = a + b V for eroding
// rods, and what it implies through the Alekseevskii-Tate balance (thesis seed 000 §5.2,
// eq. 5.2-5.5). SI units: m/s, kg/m^3, Pa.
#include <vector>

namespace ballista::penetration {

struct LinearFit {
  double a = 0;   ///< intercept [m/s]
  double b = 0;   ///< slope [1]
  double r2 = 0;  ///< coefficient of determination [1]
};

/// Least-squares fit of eq. 5.2, U = a + b V, to (V_i, U_i); at least two distinct V.
LinearFit fit_orphal_anderson(const std::vector<double>& V, const std::vector<double>& U);

/// Dynamic strength difference R - Y implied by U = a + b V in eq. 3.9 (eq. 5.3) [Pa]:
///   R - Y = rho_p ((1-b) V - a)^2 / 2 - rho_t (a + b V)^2 / 2.
/// Eq. 5.3 as printed reads "(a^2 + 2ab + b^2 V^2)"; the middle term is 2 a b V (expanding the
/// balance above; test_orphal_anderson.cpp checks the two against each other).
double orphal_anderson_strength_difference(double a, double b, double rho_p, double rho_t, double V);

/// V_m where d(R - Y)/dV = 0, eq. 5.4 [m/s]; throws if eq. 5.5 is zero (no extremum: R - Y is linear).
double orphal_anderson_extremum_velocity(double a, double b, double rho_p, double rho_t);

/// d^2(R - Y)/dV^2 = rho_p (b - 1)^2 - rho_t b^2, eq. 5.5 [kg/m^3]: < 0 maximum, > 0 minimum at V_m.
double orphal_anderson_curvature(double b, double rho_p, double rho_t);

/// The slope that makes eq. 5.5 zero, b = 1 / (1 + sqrt(rho_t/rho_p)) (the hydrodynamic slope,
/// thesis §5.2: 0.743 tungsten, 0.664 copper into sandstone).
double orphal_anderson_hydrodynamic_slope(double rho_p, double rho_t);

}  // namespace ballista::penetration
