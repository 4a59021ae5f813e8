#pragma once
// Equations of state of detonation products (seed 001, "Jones-Wilkins-Lee (JWL) Equation of
// State" and "Volume Burn Algorithm"), in the seed's variables: X = V / V0 = rho0 / rho (the
// relative volume, J) and E the internal energy per unit *initial* volume (J/m^3).
//
// JWL (E.L. Lee, H.C. Hornig & J.W. Kury, UCRL-50422, 1968; seed 001):
//   P(X, E) = A (1 - w / (R1 X)) e^{-R1 X} + B (1 - w / (R2 X)) e^{-R2 X} + w E / X
//   isentropes: P_s(X) = A e^{-R1 X} + B e^{-R2 X} + C X^{-(w+1)},
//               E_s(X) = (A / R1) e^{-R1 X} + (B / R2) e^{-R2 X} + (C / w) X^{-w}
// (dE_s/dX = -P_s and P(X, E_s(X)) = P_s(X): every isentrope has E -> 0 as X -> inf, so a state's
// E is the whole work its expansion can still do).
// Ideal gas (gamma law): P = (gamma - 1) E / X.
//
// Chapman-Jouguet state (Rayleigh line P = rho0 D^2 (1 - X) tangent to the products' isentrope):
//   X_CJ = 1 - P_CJ / (rho0 D^2); for the ideal gas P_CJ = rho0 D^2 / (gamma + 1) and
//   X_CJ = gamma / (gamma + 1) (W. Fickett & W.C. Davis, Detonation, 1979, §2A).
// Detonation energy per unit initial volume, from the Hugoniot energy equation at CJ
// (E_CJ - Q = P_CJ (1 - X_CJ) / 2, E_CJ = E_s,CJ(X_CJ)):
//   Q = E_s,CJ(X_CJ) - P_CJ (1 - X_CJ) / 2;  ideal gas: Q = P_CJ / (2 (gamma - 1)).
// Volume burn (seed 001): a point that lights releases Q at its current volume. The expansion
// work of the isentrope it then follows is its E = Q, which is the seed's energy statement
// int_V0^VCJ R dV + int_VCJ^inf P_DP dV = int_V0^inf P_S dV (the left side is Q); for the ideal
// gas its first pressure is P_S0 = (gamma - 1) Q = P_CJ / 2, the seed's value.
#include <cmath>

#include "core/field_key.hpp"

namespace ballista {

/// State field of the `explosive` material: the chemical energy released so far, Q F, J per m^3
/// of initial volume (summed by the points layer into EnergyTotals::chemical).
inline constexpr FieldKey<double> kChemicalEnergy{"chemical_energy"};
inline constexpr const char* kChemicalEnergyField = kChemicalEnergy.name();
/// State fields of the `explosive` material the program burn fills (points/explosive_lighting.hpp):
/// when the point lights, -1 if never (s), and the time its burn fraction takes to grow to 1 (s).
inline constexpr FieldKey<double> kLightingTime{"lighting_time"};
inline constexpr FieldKey<double> kBurnTime{"burn_time"};

struct ProductsEos {
  enum class Kind { Jwl, IdealGas };
  Kind kind = Kind::Jwl;
  double rho0 = 0.0;   ///< kg/m^3, unreacted density
  double D = 0.0;      ///< m/s, detonation speed
  double p_cj = 0.0;   ///< Pa, Chapman-Jouguet pressure (ideal gas: rho0 D^2 / (gamma + 1))
  double A = 0.0, B = 0.0;    ///< Pa (JWL)
  double R1 = 0.0, R2 = 0.0;  ///< 1 (JWL)
  double omega = 0.0;         ///< 1 (JWL; the ideal gas's gamma - 1)
  double gamma = 0.0;         ///< 1 (ideal gas)
};

/// The ideal-gas products of an explosive of density rho0, detonation speed D and gamma.
ProductsEos ideal_gas_products(double rho0, double D, double gamma);

/// Pressure P(X, E), Pa.
double products_pressure(const ProductsEos& e, double X, double E);

/// Relative volume of the CJ state, X_CJ = 1 - P_CJ / (rho0 D^2).
double cj_volume(const ProductsEos& e);

/// Constant C of the JWL isentrope through the CJ state (P_s(X_CJ) = P_CJ), Pa.
double jwl_cj_isentrope_constant(const ProductsEos& e);

/// Pressure and energy per initial volume on the isentrope through the CJ state at X (Pa, J/m^3).
double cj_isentrope_pressure(const ProductsEos& e, double X);
double cj_isentrope_energy(const ProductsEos& e, double X);

/// Detonation energy per unit initial volume Q (J/m^3) from the CJ state (above).
double detonation_energy(const ProductsEos& e);

/// Isentropic (dP/dX)_s at (X, E), Pa: the partial dP/dX at fixed E minus (dP/dE) P.
double products_isentropic_slope(const ProductsEos& e, double X, double E);

/// Sound speed of the products, c^2 = (X^2 / rho0) (-dP/dX)_s, m/s (NaN if not real).
double products_sound_speed(const ProductsEos& e, double X, double E);

/// Gurney velocities (R.W. Gurney, BRL Report 405, 1943; P.W. Cooper, Explosives Engineering,
/// 1996, ch. 27): sqrt(2E) the explosive's Gurney constant (m/s), M the metal and C the charge
/// mass (per unit length or area: only M/C enters).
///   cylinder:            V = sqrt(2E) (M/C + 1/2)^{-1/2}
///   open-faced sandwich: V = sqrt(2E) [((1 + 2 M/C)^3 + 1) / (6 (1 + M/C)) + M/C]^{-1/2}
///   symmetric sandwich:  V = sqrt(2E) (M/C + 1/3)^{-1/2}
double gurney_cylinder(double sqrt2E, double M_over_C);
double gurney_open_sandwich(double sqrt2E, double M_over_C);
double gurney_symmetric_sandwich(double sqrt2E, double M_over_C);

}  // namespace ballista
