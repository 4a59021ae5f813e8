#pragma once
// Strength-corrected steady jet penetration models reviewed in the thesis seed 000, chapter 3:
// Pack-Evans (eq. 3.5), Eichelberger (eq. 3.6-3.8), Gladkikh (eq. 3.10), Grove (eq. 3.11-3.13).
// SI units: densities kg/m^3, lengths m, velocities m/s, strengths Pa.
#include "penetration/interface_balance.hpp"

namespace ballista::penetration {

/// Where the strength penalty of Pack-Evans sits. Eq. 3.5 as printed has it inside the square
/// root; the extraction formulas of §6.4 (eq. 6.15-6.16) invert the form with it outside, and
/// Tables 6.5-6.7 are reproduced only with that form (tests/unit/penetration/test_pack_evans_fit.cpp).
enum class PackEvansForm {
  kPenaltyInsideRoot,   ///< eq. 3.5: P = L sqrt(lambda rho_p/rho_t (1 - x)) + r
  kPenaltyOutsideRoot,  ///< as inverted by eq. 6.15-6.16: P = L sqrt(lambda rho_p/rho_t) (1 - x) + r
};

struct PackEvansInput {
  double L = 0;        ///< jet length [m]
  double lambda = 1;   ///< particulation factor [1], > 0
  double rho_p = 0;    ///< jet density [kg/m^3]
  double rho_t = 0;    ///< target density [kg/m^3]
  double alpha = 0;    ///< density-dependent coefficient of the penalty [1]
  double sigma_y = 0;  ///< target yield strength [Pa]
  double V = 0;        ///< jet velocity [m/s]
  double r = 0;        ///< penetration channel radius (secondary penetration) [m]
  PackEvansForm form = PackEvansForm::kPenaltyInsideRoot;
};

/// Dimensionless penalty x = alpha sigma_y / (rho_p V^2) of eq. 3.5.
double pack_evans_penalty(const PackEvansInput& in);
/// Depth of eq. 3.5 (or the §6.4 form); throws if the penalty x exceeds 1 (no real depth).
double pack_evans_depth(const PackEvansInput& in);

struct EichelbergerInput {
  double L = 0;       ///< jet length [m]
  double lambda = 1;  ///< statistical jet factor [1], > 0
  double rho_p = 0;   ///< jet density [kg/m^3]
  double rho_t = 0;   ///< target density [kg/m^3]
  double R = 0;       ///< target dynamic resistance [Pa]
  double Y = 0;       ///< jet dynamic strength [Pa]
  double V = 0;       ///< jet velocity [m/s]
};

struct SteadyPenetration {
  double U = 0;  ///< penetration velocity [m/s]
  double P = 0;  ///< depth [m] (0 if the target is not penetrated)
  InterfaceRegime regime = InterfaceRegime::kEroding;
};

/// Eq. 3.6 for U with sigma = R - Y (eq. 3.7), then the depth of eq. 3.8. Throws in the rigid
/// regime (V - U = 0: eq. 3.8 does not apply).
SteadyPenetration eichelberger(const EichelbergerInput& in);

/// Gladkikh et al. depth for a constant-diameter jet with a linear velocity gradient, eq. 3.10:
/// P = L gamma [((2 + gamma) G - 2 (1 + gamma) sqrt(G + gamma)) / (G - 1)],
/// gamma = sqrt(rho_p/rho_t), G = V_tip/V_tail > 1. Throws if G <= 1 (the model needs a
/// gradient) or if the bracket is <= 0 (eq. 3.10 as printed gives no positive depth there).
double gladkikh_depth(double L, double rho_p, double rho_t, double V_tip, double V_tail);

struct GroveInput {
  double L = 0;      ///< jet length [m]
  double rho_d = 0;  ///< distended (porous) jet density before impact [kg/m^3]
  double rho_s = 0;  ///< solid (pore-free) jet density [kg/m^3], >= rho_d
  double rho_t = 0;  ///< target density [kg/m^3]
  double R = 0;      ///< target resistance [Pa]
  double Y = 0;      ///< jet strength [Pa]
  double V = 0;      ///< jet velocity [m/s]
};

struct GroveResult {
  double phi = 0;  ///< jet porosity 1 - rho_d/rho_s [1]
  SteadyPenetration steady;
};

/// Grove: target pressure R + rho_t U^2/2 (eq. 3.11) = jet pressure Y + rho_d (V-U)^2 (1+phi)/2
/// (eq. 3.12) for U, then the depth of eq. 3.13. Throws in the rigid regime.
GroveResult grove(const GroveInput& in);

}  // namespace ballista::penetration
