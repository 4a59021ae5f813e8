#pragma once
// Harvey, Grove & Zhan stressed-rock penetration correlation (SPE 2012) as given in the thesis
// seed 000, eq. 3.14-3.18. The published correlation is in US field units (psi; porosity in
// percent); it is evaluated in those units inside harvey_depth and every argument and result here
// is SI (Pa, porosity as a fraction, depth in the unit of P_ref, normally m).
namespace ballista::penetration {

inline constexpr double kPascalPerPsi = 6894.757293168361;  // 1 psi = 0.45359237 kgf / (0.0254 m)^2

struct HarveyInput {
  double P_ref = 0;      ///< depth in a formation with F_BI = 10000 psi [m]
  double alpha0 = 0;     ///< charge coefficient [1/Pa] (published in 1/psi: alpha0_psi = alpha0 * kPascalPerPsi)
  double sigma_ucs = 0;  ///< unconfined compressive strength [Pa]
  double P_c = 0;        ///< confining stress (overburden) [Pa]
  double P_p = 0;        ///< pore fluid pressure [Pa]
  double porosity = 0;   ///< porosity phi as a fraction in [0, 1] (eq. 3.17 uses percent)
};

struct HarveyResult {
  double depth = 0;  ///< P of eq. 3.14 [m]
  double F_BI = 0;   ///< ballistic indicator function, eq. 3.15 [Pa]
  double P_eff = 0;  ///< effective stress, eq. 3.16 [Pa]
  double a = 0;      ///< ballistic pore pressure coefficient, eq. 3.17 [1]
  double b = 0;      ///< stress influence coefficient, eq. 3.18 [1]
};

/// Eq. 3.14-3.18. Eq. 3.16 is printed "P_eff = P_c = a P_p"; read as P_eff = P_c - a P_p
/// (effective stress: confining stress less the pore-pressure share, Grove et al.).
HarveyResult harvey_depth(const HarveyInput& in);

}  // namespace ballista::penetration
