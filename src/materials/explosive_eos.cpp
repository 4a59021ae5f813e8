#include "materials/explosive_eos.hpp"

#include <algorithm>

namespace ballista {

ProductsEos ideal_gas_products(double rho0, double D, double gamma) {
  ProductsEos e;
  e.kind = ProductsEos::Kind::IdealGas;
  e.rho0 = rho0;
  e.D = D;
  e.gamma = gamma;
  e.omega = gamma - 1.0;
  e.p_cj = rho0 * D * D / (gamma + 1.0);  // Fickett & Davis §2A, strong-detonation limit
  return e;
}

double products_pressure(const ProductsEos& e, double X, double E) {
  if (e.kind == ProductsEos::Kind::IdealGas) return (e.gamma - 1.0) * E / X;
  // Seed 001, "JWL Equation of State".
  return e.A * (1.0 - e.omega / (e.R1 * X)) * std::exp(-e.R1 * X) +
         e.B * (1.0 - e.omega / (e.R2 * X)) * std::exp(-e.R2 * X) + e.omega * E / X;
}

double cj_volume(const ProductsEos& e) { return 1.0 - e.p_cj / (e.rho0 * e.D * e.D); }

double jwl_cj_isentrope_constant(const ProductsEos& e) {
  const double X = cj_volume(e);
  return (e.p_cj - e.A * std::exp(-e.R1 * X) - e.B * std::exp(-e.R2 * X)) * std::pow(X, e.omega + 1.0);
}

double cj_isentrope_pressure(const ProductsEos& e, double X) {
  if (e.kind == ProductsEos::Kind::IdealGas)
    return e.p_cj * std::pow(cj_volume(e) / X, e.gamma);  // P X^gamma constant
  // Seed 001, "Expansion Isentrope".
  return e.A * std::exp(-e.R1 * X) + e.B * std::exp(-e.R2 * X) +
         jwl_cj_isentrope_constant(e) * std::pow(X, -(e.omega + 1.0));
}

double cj_isentrope_energy(const ProductsEos& e, double X) {
  if (e.kind == ProductsEos::Kind::IdealGas) return cj_isentrope_pressure(e, X) * X / (e.gamma - 1.0);
  // The integral of P_s from X to infinity.
  return e.A / e.R1 * std::exp(-e.R1 * X) + e.B / e.R2 * std::exp(-e.R2 * X) +
         jwl_cj_isentrope_constant(e) / e.omega * std::pow(X, -e.omega);
}

double detonation_energy(const ProductsEos& e) {
  // Hugoniot energy equation at the CJ point: E_CJ - Q = P_CJ (V0 - V_CJ) / 2 per initial volume.
  const double X = cj_volume(e);
  return cj_isentrope_energy(e, X) - 0.5 * e.p_cj * (1.0 - X);
}

double products_isentropic_slope(const ProductsEos& e, double X, double E) {
  const double P = products_pressure(e, X, E);
  if (e.kind == ProductsEos::Kind::IdealGas) return -e.gamma * P / X;  // P X^gamma constant
  // d/dX at fixed E of each JWL term, then dP/dE dE/dX = (w / X)(-P) along the isentrope.
  auto term = [&](double a, double r) {
    const double ex = std::exp(-r * X);
    return a * (e.omega / (r * X * X) * ex - r * (1.0 - e.omega / (r * X)) * ex);
  };
  const double dP_dX_E = term(e.A, e.R1) + term(e.B, e.R2) - e.omega * E / (X * X);
  return dP_dX_E - e.omega / X * P;
}

double products_sound_speed(const ProductsEos& e, double X, double E) {
  const double c2 = X * X / e.rho0 * (-products_isentropic_slope(e, X, E));
  // No real sound speed is a state outside the EOS: NaN, so that the stable step reports it.
  return c2 > 0.0 ? std::sqrt(c2) : std::nan("");
}

double gurney_cylinder(double sqrt2E, double m) { return sqrt2E / std::sqrt(m + 0.5); }

double gurney_open_sandwich(double sqrt2E, double m) {
  return sqrt2E / std::sqrt((std::pow(1.0 + 2.0 * m, 3) + 1.0) / (6.0 * (1.0 + m)) + m);
}

double gurney_symmetric_sandwich(double sqrt2E, double m) { return sqrt2E / std::sqrt(m + 1.0 / 3.0); }

}  // namespace ballista
