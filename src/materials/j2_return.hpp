#pragma once
// Radial return for von Mises (J2) plasticity with linear isotropic hardening, shared by the J2
// family of models.
//
// Source: J.C. Simo & T.J.R. Hughes, Computational Inelasticity, Springer 1998, §3.3.1 and
// Box 3.1 (closest-point projection onto the von Mises cylinder, which for J2 is the exact
// backward-Euler solution of the rate equations). Written here in terms of the von Mises
// equivalent stress q = sqrt(3/2)|s| and the equivalent plastic strain eps_p = sqrt(2/3)|eps^p|
// (Simo & Hughes write |xi| - sqrt(2/3) K(alpha) with alpha = eps_p; the two are identical after
// multiplying their yield function by sqrt(3/2)):
//   f_trial = q_trial - sigma_y(eps_p_n),     sigma_y(e) = sigma_y0 + H e
//   delta_eps_p = f_trial / (3G + H)          (Box 3.1 step 4: Delta gamma = f/(2G(1 + H/3G)),
//                                               delta_eps_p = sqrt(2/3) Delta gamma)
//   s_{n+1} = (1 - 3G delta_eps_p / q_trial) s_trial
// after which q_{n+1} = sigma_y(eps_p_n + delta_eps_p) exactly (consistency).
#include "core/tensor.hpp"

namespace ballista {

/// Result of one radial return.
struct J2Return {
  double delta_eqps = 0.0;   ///< increment of equivalent plastic strain (0 if elastic)
  double plastic_work = 0.0; ///< int sigma_y d(eps_p) over the increment, J/m^3
};

/// Linear isotropic hardening flow stress sigma_y(eps_p) = sigma_y0 + H eps_p.
inline double j2_flow_stress(double yield0, double hardening, double eqps) {
  return yield0 + hardening * eqps;
}

/// Returns the stress `sigma` (any frame; only its deviator changes) to the von Mises yield surface
/// if the trial state lies outside it. `eqps` is the equivalent plastic strain at t_n on entry and
/// at t_{n+1} on exit; G is the shear modulus, yield0 > 0 the initial yield stress, hardening >= 0
/// the plastic modulus H. The plastic work over the increment is the exact integral of the flow
/// stress over the plastic-strain increment, 0.5 (sigma_y(eps_n) + sigma_y(eps_{n+1})) delta_eps_p
/// (trapezoidal rule, exact for linear hardening), so that summed over steps it equals
/// int sigma_y d(eps_p) regardless of the step size.
inline J2Return j2_radial_return(Mat3& sigma, double& eqps, double G, double yield0, double hardening) {
  J2Return r;
  const double mean = trace(sigma) / 3.0;
  Mat3 s = sigma;
  s(0, 0) -= mean; s(1, 1) -= mean; s(2, 2) -= mean;
  const double q_trial = std::sqrt(1.5 * ddot(s, s));
  const double sy_n = j2_flow_stress(yield0, hardening, eqps);
  const double f = q_trial - sy_n;
  if (!(f > 0.0)) return r;  // elastic (also keeps a NaN trial from being "returned")
  const double de = f / (3.0 * G + hardening);
  const double scale = 1.0 - 3.0 * G * de / q_trial;  // = sigma_y(n+1)/q_trial, in (0, 1)
  s *= scale;
  s(0, 0) += mean; s(1, 1) += mean; s(2, 2) += mean;
  sigma = s;
  const double sy_np1 = j2_flow_stress(yield0, hardening, eqps + de);
  eqps += de;
  r.delta_eqps = de;
  r.plastic_work = 0.5 * (sy_n + sy_np1) * de;
  return r;
}

}  // namespace ballista
