#pragma once
// Exact solution of uniaxial strain for von Mises (J2) plasticity with linear isotropic and
// linear kinematic hardening: verification CATALOGUE A2 and its hardening variants (thesis seed
// 000 §4.1.1.2, Fig. 4.4-4.6; R.M. Brannon, "Elements of phenomenological plasticity", in
// Shock Wave Science and Technology Reference Library vol. 2 (2007), uniaxial strain).
//
// Strain measure. The argument is the axial logarithmic strain e = ln F11 (F = diag(F11, 1, 1),
// no rotation). In uniaxial strain L11 = dF11/dt / F11 exactly, so D11 = de/dt and the rate
// equations of the hypoelastic model (thesis seed 000 §2.3) integrate in e with no
// approximation: this is the continuum answer, independent of any step size. A discrete update
// fed the eq. 4.10 increments F_{n+1}/F_n - 1 integrates sum (F_{n+1}/F_n - 1) = ln F11 +
// sum (d ln F)^2/2 + ..., so it differs from this solution by O(step) (see a2_uniaxial_strain.cpp
// for the bound used as tolerance).
//
// Reduction to one scalar. With e the only strain, every deviator is a multiple of
// diag(2, -1, -1)/3; write q = sigma11 - sigma22 (signed, von Mises stress |q|),
// beta = alpha11 - alpha22 for the deviatoric backstress alpha, and eps_p the equivalent plastic
// strain. Then (Simo & Hughes, Computational Inelasticity 1998, §3.3 with Prager-Ziegler
// kinematic hardening d alpha = (2/3) H_kin d eps^p):
//   mean stress         sigma_m = K e                       (plastic flow is isochoric)
//   yield               |q - beta| = sigma_y0 + H_iso eps_p =: r
//   elastic             dq = 2G de
//   plastic, n = sign(q - beta):  d eps_p = 2G |de| / (3G + H_iso + H_kin),
//                       dq = n (H_iso + H_kin) d eps_p,   d beta = n H_kin d eps_p
//   sigma11 = sigma_m + 2q/3,  sigma22 = sigma33 = sigma_m - q/3.
// Along a monotone piece of the strain history the response is one elastic part up to the yield
// event (closed form) followed by one linear plastic part, so advancing from e to e' is exact
// ("event-based closed form"). The caller must split the history where e changes direction.
#include <vector>

namespace ballista {

/// Material constants of the A2 family, SI.
struct J2UniaxialParams {
  double bulk = 0.0;    ///< K, Pa
  double shear = 0.0;   ///< G, Pa
  double yield = 0.0;   ///< initial uniaxial yield stress sigma_y0 = sqrt(3) tau_y, Pa
  double h_iso = 0.0;   ///< linear isotropic plastic modulus: r = sigma_y0 + h_iso eps_p, Pa
  double h_kin = 0.0;   ///< linear kinematic (Prager) modulus: d alpha = 2/3 h_kin d eps^p, Pa
};

/// A point where plastic flow starts (elastic -> plastic, on first loading or on reversal).
struct YieldEvent {
  double e = 0.0;        ///< axial log strain at the event
  double sigma11 = 0.0;  ///< Pa
  double sigma22 = 0.0;  ///< Pa (= sigma33)
  double q = 0.0;        ///< sigma11 - sigma22 at the event, Pa
  double beta = 0.0;     ///< backstress alpha11 - alpha22 at the event, Pa
  double radius = 0.0;   ///< yield radius sigma_y0 + h_iso eps_p at the event, Pa
};

class UniaxialStrainJ2 {
 public:
  explicit UniaxialStrainJ2(const J2UniaxialParams& p);

  /// Advances the strain monotonically from the current e to e_new (exact).
  void advance_to(double e_new);

  double e() const { return e_; }
  double q() const { return q_; }
  double beta() const { return beta_; }
  double eqps() const { return eqps_; }
  double radius() const { return p_.yield + p_.h_iso * eqps_; }
  double mean_stress() const { return p_.bulk * e_; }
  double sigma11() const { return mean_stress() + 2.0 * q_ / 3.0; }
  double sigma22() const { return mean_stress() - q_ / 3.0; }
  /// Pressure P = -I1/3 (CATALOGUE sign convention), Pa.
  double pressure() const { return -mean_stress(); }
  /// True if the last advance ended with plastic flow.
  bool plastic() const { return plastic_; }
  const std::vector<YieldEvent>& yield_events() const { return events_; }
  const J2UniaxialParams& params() const { return p_; }

 private:
  J2UniaxialParams p_;
  double e_ = 0.0, q_ = 0.0, beta_ = 0.0, eqps_ = 0.0;
  bool plastic_ = false;
  int last_dir_ = 0;
  std::vector<YieldEvent> events_;
};

/// The A2 family evaluated along a strain history e_k (consecutive samples must bracket every
/// change of direction, e.g. include the rows of an F-table): stresses at every sample.
struct UniaxialStrainSeries {
  std::vector<double> e, sigma11, sigma22, q, pressure, eqps, beta, radius;
  std::vector<YieldEvent> events;
};
UniaxialStrainSeries uniaxial_strain_j2_series(const J2UniaxialParams& p, const std::vector<double>& e);

}  // namespace ballista
