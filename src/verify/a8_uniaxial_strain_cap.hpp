#pragma once
// CATALOGUE A8, compressive uniaxial strain through a linear Drucker-Prager surface into its
// elliptical cap (thesis seed 000 §4.1.1.4, Fig. 4.10a, b): (a) the cap fixed at P0: the stress
// meets the flat cone, climbs it, turns onto the cap and settles where the cap's slope is
// d sqrt(J2)/dI1 = 1/(2 sqrt3); (b) the cap moving with the crush curve (eq. 4.5-4.6): the stress
// stays on the expanding surface, the cap on the crush curve of the plastic volumetric strain.
// Both against the reference of uniaxial_strain_cap.hpp, on the model's reduce_geo parameters.
// The thesis calls these trend tests ("analytical solutions ... do not currently exist"); with the
// deviator's direction fixed by uniaxial strain the response reduces to an ODE in the strain, which
// the reference integrates to round-off.
#include "materials/material.hpp"
#include "verify/hydrostatic_compare.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

struct A8Problem {
  /// The sandstone of A4 with a shallower cone and a rounder cap, so that uniaxial strain meets the
  /// cone first (the elastic path's slope sqrt(J2)/(-I1) = 2G/(3 sqrt3 K) = 0.27 exceeds FSLOPE)
  /// and the cap's turn is wide (CR = 1): the cone is met at I1 = -12.6 MPa, the cap begins at
  /// kappa = -77 MPa.
  GeoSandstone rock = [] {
    GeoSandstone r;
    r.fslope = 0.15;
    r.cap_ratio = 1.0;
    return r;
  }();
  double strain = 0.03;  ///< final compressive log strain -ln F11
  int steps = 3000;      ///< driver steps (headline run; N/2 and N/4 for the order)
  int plot_every = 10;
};

/// Runs A8 (both parts); not applicable without reduce_geo.
VerifyCase run_a8(const MaterialFactory& f, const A8Problem& problem = {});

}  // namespace ballista
