#pragma once
// CATALOGUE A1, frame indifference (thesis seed 000 §4.1.1.1, Fig. 4.1-4.2; Uintah Arenisca test
// 01): an elastic element is stretched F11: 1 -> 0.998 over t in [0, 1] while it turns 360 deg about
// z. The unrotated stress must be that of the unrotated stretch alone,
//   sigma_bar11 = (K + 4G/3) ln F11(t),  every other component 0,
// and the spatial stress that tensor turned by theta = 2 pi t:
//   sigma_xx = sigma_bar11 cos^2 theta, sigma_yy = sigma_bar11 sin^2 theta,
//   sigma_xy = sigma_bar11 sin theta cos theta.
// (Small-strain isotropic elasticity in the logarithmic strain: exact for the hypoelastic
// models, which integrate D = d ln F11/dt; a hyperelastic model differs by O(ln F11).)
#include <cmath>
#include <numbers>

#include "core/tensor.hpp"
#include "materials/material.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

struct A1Problem {
  double bulk = 10000.0;    ///< K, Pa (catalogue)
  double shear = 15000.0;   ///< G, Pa (catalogue)
  double density = 1000.0;  ///< kg/m^3 (any: the driver has no inertia)
  double F11_end = 0.998;   ///< F11 at t = 1
  double turns = 1.0;       ///< superimposed rotation about z over t in [0, 1], turns
  int steps = 20000;        ///< one run (midpoint strain increment: no rotation error, see run_a1)
  int samples = 200;        ///< recorded (and plotted) samples over [0, 1]

  double F11(double t) const { return 1.0 + (F11_end - 1.0) * t; }
  double theta(double t) const { return 2.0 * std::numbers::pi * turns * t; }
  /// Analytic unrotated stress: (K + 4G/3) ln F11 in 11, zero elsewhere.
  Mat3 sigma_bar(double t) const { return Mat3::diag((bulk + 4.0 * shear / 3.0) * std::log(F11(t)), 0.0, 0.0); }
  /// Analytic spatial stress: sigma_bar turned by theta about z.
  Mat3 sigma(double t) const { return rotate(rotation_about(Vec3{{0.0, 0.0, 1.0}}, theta(t)), sigma_bar(t)); }
};

/// Runs A1 on the model's reduce_elastic parameters (not applicable without that hook).
VerifyCase run_a1(const MaterialFactory& f, const A1Problem& problem = {});

}  // namespace ballista
