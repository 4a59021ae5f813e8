// The closed forms of j2_deviatoric_legs.hpp.
#include "verify/j2_deviatoric_legs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ballista {

namespace {

const double kSqrt6 = std::sqrt(6.0), kSqrt2 = std::sqrt(2.0);

double dot(const Dev2& a, const Dev2& b) { return a[0] * b[0] + a[1] * b[1]; }

/// First tau >= 0 at which s0 + tau u leaves the circle of radius R (s0 on or inside it): 0 if
/// s0 is on the circle and u points out, infinity if u = 0.
double exit_fraction(const Dev2& s0, const Dev2& u, double R) {
  const double a = dot(u, u);
  if (a == 0.0) return std::numeric_limits<double>::infinity();
  const double b = 2.0 * dot(s0, u), c = dot(s0, s0) - R * R;
  // On the circle (to round-off of R^2) and moving out: plastic at once.
  if (c >= -1e-12 * R * R && b > 0.0) return 0.0;
  const double disc = std::max(0.0, b * b - 4.0 * a * c);
  return std::max(0.0, (-b + std::sqrt(disc)) / (2.0 * a));
}

}  // namespace

Dev2 deviatoric_components(const std::array<double, 3>& d) {
  return {(2.0 * d[0] - d[1] - d[2]) / kSqrt6, (d[1] - d[2]) / kSqrt2};
}

std::array<double, 3> diagonal_of(const Dev2& s, double m) {
  return {m + 2.0 * s[0] / kSqrt6, m - s[0] / kSqrt6 + s[1] / kSqrt2, m - s[0] / kSqrt6 - s[1] / kSqrt2};
}

double J2PerfectParams::radius() const { return kSqrt2 * tau_y; }

J2DeviatoricLegs::J2DeviatoricLegs(const J2PerfectParams& p, std::vector<std::array<double, 3>> legs)
    : p_(p), legs_(std::move(legs)) {
  Dev2 s{0.0, 0.0};
  double m = 0.0;
  for (size_t k = 0; k < legs_.size(); ++k) {
    s_start_.push_back(s);
    mean_start_.push_back(m);
    const Dev2 de = deviatoric_components(legs_[k]);
    tau_yield_.push_back(exit_fraction(s, {2.0 * p_.shear * de[0], 2.0 * p_.shear * de[1]}, p_.radius()));
    s = deviator(k, 1.0);
    m += p_.bulk * (legs_[k][0] + legs_[k][1] + legs_[k][2]);
  }
}

Dev2 J2DeviatoricLegs::deviator(size_t leg, double tau) const {
  const Dev2 de = deviatoric_components(legs_[leg]);
  const Dev2& s0 = s_start_[leg];
  const double G2 = 2.0 * p_.shear, R = p_.radius();
  const double ty = tau_yield_[leg];
  if (tau <= ty) return {s0[0] + G2 * de[0] * tau, s0[1] + G2 * de[1] * tau};
  // On the circle from tau_y: the angle from de relaxes as tan(psi/2) ~ exp(-2G|de| tau / R).
  const double mag = std::sqrt(dot(de, de));
  const Dev2 d{de[0] / mag, de[1] / mag}, n{-d[1], d[0]};
  const double psi0 = yield_angle(leg);
  const double psi = 2.0 * std::atan(std::tan(0.5 * psi0) * std::exp(-G2 * mag * (tau - ty) / R));
  return {R * (std::cos(psi) * d[0] + std::sin(psi) * n[0]), R * (std::cos(psi) * d[1] + std::sin(psi) * n[1])};
}

double J2DeviatoricLegs::yield_angle(std::size_t leg) const {
  const double ty = tau_yield_[leg];
  if (ty > 1.0) return 0.0;
  const Dev2 de = deviatoric_components(legs_[leg]);
  const Dev2& s0 = s_start_[leg];
  const double G2 = 2.0 * p_.shear;
  const Dev2 sy{s0[0] + G2 * de[0] * ty, s0[1] + G2 * de[1] * ty};
  return std::atan2(de[0] * sy[1] - de[1] * sy[0], dot(de, sy));
}

std::array<double, 3> J2DeviatoricLegs::stress(size_t leg, double tau) const {
  const auto& l = legs_[leg];
  return diagonal_of(deviator(leg, tau), mean_start_[leg] + p_.bulk * tau * (l[0] + l[1] + l[2]));
}

}  // namespace ballista
