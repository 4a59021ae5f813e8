#pragma once
// The constants of the PMB bond (Silling & Askari, Comput. Struct. 83 (2005) 1526; the
// "Microelastic material" of Sandia's EMU, seed 001_65d50031991c2cdb.txt) from a material's elastic
// moduli: the family moments that calibrate them (continuum integrals or the lattice family), the
// micromodulus c, the critical stretch s00, the micro-plastic yield stretch, the constants of a
// bond between two materials, and the surface correction of points near a free surface.
//
// One relation underlies the calibration in any dimension: the energy density of a dilatation eps
// is W = c eps^2 m1 / 4 (S&A 2005 eq. 21 summed over the family), and a crack opening through its
// critical stretch releases G = c s0^2 m2 / 2 per unit area (the discrete form of eq. 25), with
// m1 = sum_j |xi_j| beta_j V_j and m2 the sum over the bonds crossing a plane (bond_family.hpp).
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "materials/material.hpp"
#include "peridynamics/bond_family.hpp"

namespace ballista {

/// Bulk and shear modulus of a library material at its reference state, probed by driving one
/// point through its own kernel with tiny volumetric and shear strain increments.
struct ProbedModuli {
  double bulk = 0.0;   ///< Pa
  double shear = 0.0;  ///< Pa
};
ProbedModuli probe_moduli(const Material& material);

namespace pd {

/// The moments m1 and m2 the bond constants are calibrated with. Continuum: the integrals over the
/// horizon sphere, exact there: 3D m1 = pi delta^4, m2 = pi delta^5/5 (S&A 2005); 2D per unit
/// thickness m1 = 2 pi delta^3/3, m2 = delta^4/2 (Ha & Bobaru, Int. J. Fract. 162 (2010) 229:
/// c = 9E/(pi h delta^3) in plane stress). On the lattice the sums differ (K_PD = 0.90 K and
/// G = 0.87 G0 at m = 3 with partial volumes), so `lattice` takes the same relations over the
/// family of an interior point of the lattice of spacing dx (lattice_moments, bond_family.hpp):
/// exact K and G0 for interior points.
LatticeMoments calibration_moments(bool lattice, double delta, double dx, bool partial, int dim);

/// The dilatational modulus of a material in the model's dimension: the bulk modulus K in 3D; in
/// 2D the in-plane bulk modulus K2, K + G/3 in plane strain and E/(2(1 - nu)) in plane stress.
double dilatational_modulus(const ProbedModuli& moduli, int dim, bool plane_stress);

/// Micromodulus of a material's bonds, N/m^6: W = c eps^2 m1 / 4 equals the continuum 9 K eps^2/2
/// in 3D and 2 K2 eps^2 in 2D (eps in both in-plane directions), so c = 18 K/m1 (3D; with the
/// continuum m1, c = 18 K/(pi delta^4), S&A 2005 eq. 22) or c = 8 K2/m1 (2D). `kd` is
/// dilatational_modulus.
double micromodulus(double kd, double m1, int dim);

/// Critical stretch s00 of a material's bonds: `given` (peridynamics.critical_stretch), or from
/// the fracture energy, the work per unit area of crack to break every bond across it (S&A 2005
/// §5: the bond energies w(s00) summed over the bonds a plane cuts, G0 = m2 w(s00)/|xi|):
/// - elastic bonds, w = c s^2 |xi| / 2: G0 = c s00^2 m2 / 2, s00 = sqrt(2 G0/(c m2)) (with the
///   continuum m2 in 3D sqrt(5 G0/(9 K delta)), S&A 2005 eq. 25);
/// - micro-plastic bonds (elastic to the yield stretch s_y, flat beyond: seed 001, "Micro-Elastic
///   and -Plastic Materials") that yield before they break, w = c |xi| s_y (s - s_y/2):
///   G0 = c m2 s_y (s00 - s_y/2), s00 = G0/(c m2 s_y) + s_y/2 (continuous with the elastic rule
///   at s00 = s_y). `yield_stretch` infinite: elastic bonds.
/// Neither given: infinite (bonds never fail).
double critical_stretch(std::optional<double> given, std::optional<double> fracture_energy, double c, double m2,
                        double yield_stretch = std::numeric_limits<double>::infinity());

/// Yield stretch of micro-plastic bonds: first yield of the most stretched bond (the one along the
/// load) under uniaxial stress sigma_y, s_y = sigma_y/E_PD with the modulus of the bond-based
/// model (nu = 1/4 in 3D: E = 3K/2; in 2D E = 4 K2/3 for plane stress, nu = 1/3, and plane strain
/// alike). With several materials the smallest modulus sets it (one yield stretch for every bond).
/// `kd` per material (dilatational_modulus); materials with gas[a] != 0 have no bonds.
double yield_stretch(double yield_stress, const std::vector<double>& kd, const std::vector<std::uint8_t>& gas,
                     int dim);

/// Uniaxial flow stress of micro-plastic bonds over their first-yield stress sigma_y = E_PD s_y.
/// Pulled on far beyond s_y, every bond of a family flows at +-c s_y (the sign of its stretch
/// rate), and the stress is then sigma_ij = K0 s_y <sign(s) n_i n_j> over the directions n of the
/// horizon, where the elastic state gives E_PD = K0/6 in 3D (<n n n n> = 3 sym(delta delta)/15).
/// Under uniaxial stress along z the bonds within cos(theta) > a stretch and the rest shorten;
/// zero lateral stress, <sign(s) sin^2 theta> = 0, is a^3 - 3a + 1 = 0, a = 2 cos(4 pi/9), so the
/// plateau is sigma_zz = K0 s_y (1 - 2a^3)/3 = 2 (1 - 2a^3) sigma_y = 1.8324 sigma_y, reached with
/// a lateral contraction of a^2/(1 - a^2) = 0.137 of the axial strain (the flow is not
/// isochoric). In 2D (E_PD = K0'/3, <n n n n> = sym(delta delta)/8 over the circle) the plateau is
/// (6/pi)(phi0 - pi/4 + sin(2 phi0)/2) sigma_y = 1.4115 sigma_y, phi0 - sin(2 phi0)/2 = pi/4. A
/// steel's yield stress from a tensile test is this plateau, not the first bond's yield (derived
/// here; tests/unit/peridynamics/test_pd_solver.cpp measures it on the lattice family).
double micro_plastic_flow_factor(int dim);

/// The constants of every material pair (a, b), at a * nmat + b.
struct PairConstants {
  std::vector<double> c;          ///< micromodulus, N/m^6
  std::vector<double> s00;        ///< critical stretch (infinite: no failure)
  std::vector<double> c_contact;  ///< micromodulus of the contact springs, N/m^6
};

/// Two materials' bond as their two half-bonds in series: c = 2 c_a c_b/(c_a + c_b) (the harmonic
/// mean), s00 the smaller one. A gas (gas[a] != 0, an explosive's products: its stiffness is its
/// pressure, gas_pass.hpp) takes no bond stiffness and none in the contact springs either (they
/// scale with c), except that products meeting a solid they were not bonded to (gas streaming
/// towards the case from deep inside the charge) are stopped by the solid's contact springs;
/// gas-gas pairs have none.
PairConstants pair_constants(const std::vector<double>& c, const std::vector<double>& s00,
                             const std::vector<std::uint8_t>& gas);

/// Surface correction (peridynamics.surface_correction: energy; Madenci & Oterkus 2014 §4.2,
/// reviewed by Le & Bobaru, Comput. Mech. 61 (2018) 499): a point near a free surface misses part
/// of its family and is softer; under a uniform dilatation its energy density is c eps^2 m1_p / 4
/// instead of the interior c eps^2 m1 / 4, so its factor is lambda_p = m1 / m1_p, and a bond is
/// stiffened by the mean of its two ends' factors (forces and energies; the critical stretch is
/// left as it is). The factors of the first n rows of `bonds` (1 for a point without bonds);
/// `vol0` per point, `m1` that of an interior point (lattice_moments).
std::vector<double> surface_factors(const BondFamily& bonds, Index n, const double* vol0, double m1);

}  // namespace pd
}  // namespace ballista
