#pragma once
// CATALOGUE A7, J2 plasticity under a strain rate misaligned with the yield normal, with fixed
// eigenvectors and transient eigenvalues (thesis seed 000 §4.1.1.2, Fig. 4.7, after Brannon &
// Leelavanichkul 2010): three legs of constant logarithmic strain rate, F diagonal throughout,
// compared with the exact solution of j2_deviatoric_legs.hpp (Krieg & Krieg 1977).
//   leg 1  uniaxial tension to twice the yield strain: the stress reaches the circle and stays
//          aligned with the strain rate (A2's path);
//   leg 2  a deviatoric rate at 60 degrees from the stress, with volumetric compression: plastic
//          at once, the stress turns on the circle towards the rate's direction;
//   leg 3  a rate at 150 degrees from the stress, with volumetric expansion: elastic unloading
//          across the circle's interior, yield again half-way, and a second turn on the circle.
// Perfect plasticity, the constants of A2 (K = 79 GPa, G = 70 GPa, tau_y = 165 MPa).
#include <array>
#include <vector>

#include "materials/material.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

struct A7Problem {
  double bulk = 79e9, shear = 70e9, tau_y = 165e6, density = 7800.0;
  /// Leg 1's axial log strain: twice the yield strain sqrt3 tau_y / (2G) = 2.04e-3.
  double uniaxial = 4.08e-3;
  /// Legs 2 and 3: deviatoric increment (norm, on E1 = diag(2,-1,-1)/sqrt6 and E2 =
  /// diag(0,1,-1)/sqrt2) at an angle from E1, and volumetric increment. 2G |de| / R = 3.0 and 3.6:
  /// the angle from the rate relaxes by e^-3 on leg 2 (60 -> 3 degrees of psi/2's tangent scale).
  double leg2_norm = 5e-3, leg2_angle_deg = 60.0, leg2_volume = -1e-3;
  double leg3_norm = 6e-3, leg3_angle_deg = 210.0, leg3_volume = 0.5e-3;
  int steps = 1000;       ///< steps per leg (headline run; N/2 and N/4 for the order)
  int plot_every = 10;    ///< plotted series keep every n-th step
  /// The three legs' diagonal log-strain increments.
  std::vector<std::array<double, 3>> legs() const;
};

/// Runs A7 on the model's reduce_j2 parameters (no hardening); not applicable without the hook.
VerifyCase run_a7(const MaterialFactory& f, const A7Problem& problem = {});

}  // namespace ballista
