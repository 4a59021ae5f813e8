#pragma once
// Exact solution of von Mises (J2) perfect plasticity driven by legs of constant logarithmic
// strain rate with fixed principal axes: CATALOGUE A7 (thesis seed 000 §4.1.1.2, Fig. 4.7, "constant
// eigen vectors with transient eigen values", after Brannon & Leelavanichkul, Int. J. Fract. 163
// (2010) 133-149: stress and strain keep their eigenvectors while the strain rate is misaligned
// with the yield normal).
//
// Reduction to the deviatoric plane. With F diagonal, D = d(ln F)/dt exactly and every deviator is
// diagonal, so it lives in the plane spanned by E1 = diag(2, -1, -1)/sqrt6 and E2 =
// diag(0, 1, -1)/sqrt2 (orthonormal under A:B). Write s = (s1, s2) there. The hypoelastic
// Prandtl-Reuss equations (Simo & Hughes, Computational Inelasticity 1998, §3.3, perfect
// plasticity) are then
//   mean stress   sigma_m = K e_v                         (plastic flow is isochoric)
//   elastic       ds/dt = 2G de/dt                        while |s| < R = sqrt2 tau_y
//   plastic       ds/dt = 2G (de/dt - (s . de/dt) s / R^2)  on |s| = R with s . de/dt > 0.
// On a leg the deviatoric strain advances by tau de (tau in [0, 1], de fixed): the elastic part is
// a straight line, whose exit through the circle is a quadratic in tau, and on the circle the angle
// psi of s measured from de obeys d psi/d tau = -(2G |de| / R) sin psi, whose solution is
//   tan(psi/2) = tan(psi0/2) exp(-2G |de| (tau - tau0) / R)
// (Krieg & Krieg, J. Pressure Vessel Technol. 99 (1977) 510-515, the exact solution behind their
// accuracy study of radial return). Every quantity is a closed form in tau: no step error.
#include <array>
#include <cstddef>
#include <vector>

namespace ballista {

/// A deviator in the (E1, E2) plane.
using Dev2 = std::array<double, 2>;

/// Components on (E1, E2) of the diagonal tensor diag(d).
Dev2 deviatoric_components(const std::array<double, 3>& d);
/// The diagonal of s1 E1 + s2 E2 + m I.
std::array<double, 3> diagonal_of(const Dev2& s, double m);

/// Constants of the A7 model, SI.
struct J2PerfectParams {
  double bulk = 0.0;   ///< K, Pa
  double shear = 0.0;  ///< G, Pa
  double tau_y = 0.0;  ///< yield in shear sqrt(J2), Pa: the circle |s| = sqrt2 tau_y
  double radius() const;
};

/// The exact state at the start of each leg and a closed-form evaluation inside it.
class J2DeviatoricLegs {
 public:
  /// `legs`: the diagonal log-strain increment of each leg, applied at constant rate from a
  /// stress-free start.
  J2DeviatoricLegs(const J2PerfectParams& p, std::vector<std::array<double, 3>> legs);

  /// Diagonal Cauchy stress at fraction tau of leg `leg` (0-based).
  std::array<double, 3> stress(std::size_t leg, double tau) const;
  /// Deviator at fraction tau of leg `leg`.
  Dev2 deviator(std::size_t leg, double tau) const;
  /// Fraction of leg `leg` at which it (re)yields: 0 if it starts plastic, > 1 if it stays elastic.
  double yield_fraction(std::size_t leg) const { return tau_yield_[leg]; }
  /// Angle psi0 (radians) of the deviator from the leg's rate where the leg starts to flow (0 if it
  /// stays elastic).
  double yield_angle(std::size_t leg) const;
  std::size_t legs() const { return legs_.size(); }

 private:
  J2PerfectParams p_;
  std::vector<std::array<double, 3>> legs_;
  std::vector<Dev2> s_start_;         ///< deviator at each leg's start
  std::vector<double> mean_start_;    ///< mean stress at each leg's start
  std::vector<double> tau_yield_;     ///< per leg, see yield_fraction
};

}  // namespace ballista
