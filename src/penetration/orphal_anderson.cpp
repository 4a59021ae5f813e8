#include "penetration/orphal_anderson.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/input_checks.hpp"

namespace ballista::penetration {

LinearFit fit_orphal_anderson(const std::vector<double>& V, const std::vector<double>& U) {
  if (V.size() != U.size())
    throw Error(
        fmt::format("orphal-anderson fit: {} velocities V but {} penetration velocities U", V.size(), U.size()));
  if (V.size() < 2) throw Error("orphal-anderson fit: needs at least two (V, U) pairs");
  const double n = static_cast<double>(V.size());
  double mv = 0, mu = 0;
  for (size_t i = 0; i < V.size(); ++i) {
    require_finite("orphal-anderson fit", "V", V[i], "m/s");
    require_finite("orphal-anderson fit", "U", U[i], "m/s");
    mv += V[i] / n;
    mu += U[i] / n;
  }
  double svv = 0, svu = 0, suu = 0;  // centred sums: no cancellation for V ~ km/s
  for (size_t i = 0; i < V.size(); ++i) {
    svv += (V[i] - mv) * (V[i] - mv);
    svu += (V[i] - mv) * (U[i] - mu);
    suu += (U[i] - mu) * (U[i] - mu);
  }
  if (!(svv > 0)) throw Error("orphal-anderson fit: all velocities V are equal; the slope b is undefined");
  LinearFit f;
  f.b = svu / svv;
  f.a = mu - f.b * mv;
  f.r2 = suu > 0 ? svu * svu / (svv * suu) : 1.0;  // U constant: the fit (b = 0) is exact
  return f;
}

double orphal_anderson_strength_difference(double a, double b, double rho_p, double rho_t, double V) {
  require_positive("orphal-anderson", "rho_p", rho_p, "kg/m^3");
  require_positive("orphal-anderson", "rho_t", rho_t, "kg/m^3");
  const double w = (1 - b) * V - a, U = a + b * V;   // V - U with U of eq. 5.2
  return 0.5 * rho_p * w * w - 0.5 * rho_t * U * U;  // eq. 3.9 solved for R - Y (= eq. 5.3)
}

double orphal_anderson_curvature(double b, double rho_p, double rho_t) {
  require_positive("orphal-anderson", "rho_p", rho_p, "kg/m^3");
  require_positive("orphal-anderson", "rho_t", rho_t, "kg/m^3");
  return rho_p * (b - 1) * (b - 1) - rho_t * b * b;  // eq. 5.5
}

double orphal_anderson_extremum_velocity(double a, double b, double rho_p, double rho_t) {
  const double den = orphal_anderson_curvature(b, rho_p, rho_t);  // eq. 5.4 denominator = eq. 5.5
  if (den == 0)
    throw Error(
        fmt::format("orphal-anderson: b = {:g} makes eq. 5.5 zero (hydrodynamic slope): R - Y is linear in V, "
                    "no extremum",
                    b));
  return (a * rho_p - (rho_p - rho_t) * a * b) / den;  // eq. 5.4
}

double orphal_anderson_hydrodynamic_slope(double rho_p, double rho_t) {
  require_positive("orphal-anderson", "rho_p", rho_p, "kg/m^3");
  require_positive("orphal-anderson", "rho_t", rho_t, "kg/m^3");
  return 1 / (1 + std::sqrt(rho_t / rho_p));  // root of eq. 5.5 in (0, 1)
}

}  // namespace ballista::penetration
