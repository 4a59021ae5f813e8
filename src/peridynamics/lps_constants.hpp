#pragma once
// The constants of the linear peridynamic solid (LPS; Silling, Epton, Weckner, Xu & Askari,
// J. Elasticity 88 (2007) 151, sec. 15; the pass itself: lps_pass.hpp) from a material's bulk and
// shear moduli, with influence function omega = 1:
// - the weighted volume of an interior point, m = sum_j |xi_j|^2 beta_j V_j (continuum
//   4 pi delta^5 / 5), which normalises the dilatation and the deviatoric stiffness 15 mu / m;
// - the critical stretch from the fracture energy;
// - the micromodulus a PMB bond would need for the same stable step and contact springs.
#include <optional>

namespace ballista::pd {

/// Moments of an interior point's family (3D, omega = 1): m = sum |xi|^2 beta V and
/// m3 = sum_{xi . e > 0} (xi . e) |xi|^2 beta V, the bonds crossing a plane of normal e. `lattice`:
/// summed over the cubic lattice of spacing dx with the partial volumes of build_bond_family;
/// else the continuum integrals m = 4 pi delta^5 / 5, m3 = pi delta^6 / 6.
struct LpsMoments {
  double m = 0.0;   ///< m^5
  double m3 = 0.0;  ///< m^6
};
LpsMoments lps_moments(bool lattice, double delta, double dx, bool partial);

/// Critical stretch of LPS bonds from the fracture energy G0: the work per unit area of crack to
/// break every bond across a plane (the argument of Silling & Askari 2005 eq. 25), each bond
/// taken with its deviatoric energy at zero dilatation, (15 mu / m) |xi|^2 s^2 beta V_i V_j for its
/// two ends: G0 = (15 mu / m) s00^2 m3, s00 = sqrt(G0 m / (15 mu m3)). With the continuum moments
/// G0 = (25/8) mu delta s00^2; Madenci & Oterkus (2014, sec. 4.3) find (3 mu + (3/4)^4 (K - 5 mu/3))
/// delta s00^2 for their ordinary state-based form, 4 % less at nu = 1/4. `given` is
/// peridynamics.critical_stretch; neither: infinite (bonds never fail).
double lps_critical_stretch(std::optional<double> given, std::optional<double> fracture_energy, double shear,
                            const LpsMoments& moments);

/// The bulk modulus of the PMB material (nu = 1/4) with the same P-wave modulus K + 4 mu / 3 as the
/// LPS material, (5/9)(K + 4 mu / 3): its micromodulus 18 K_eq / m1 sets the stable step of the
/// Silling-Askari bound (eq. 17) and the stiffness of the contact springs. Equal to K at nu = 1/4.
double lps_equivalent_bulk(double bulk, double shear);

}  // namespace ballista::pd
