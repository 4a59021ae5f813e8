// Exact triaxial solution of linear Drucker-Prager plasticity and the A3 reference data (see
// drucker_prager_triaxial.hpp for the equations and sources).
#include "verify/drucker_prager_triaxial.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace ballista {

DruckerPragerTriaxial::DruckerPragerTriaxial(const DruckerPragerParams& p) : p_(p) {
  if (!(p.bulk > 0.0) || !(p.shear > 0.0) || !(p.fslope > 0.0) || !(p.beta > 0.0) || !std::isfinite(p.peak_i1))
    throw Error("DruckerPragerTriaxial: need bulk, shear, fslope, beta > 0 and a finite peak_i1");
}

double DruckerPragerTriaxial::sqrt_j2() const { return std::abs(q_) / std::sqrt(3.0); }

double DruckerPragerTriaxial::yield_function() const { return sqrt_j2() - p_.limit(i1_); }

void DruckerPragerTriaxial::advance(double d11, double d22) {
  const double K = p_.bulk, G = p_.shear, FS = p_.fslope, s3 = std::sqrt(3.0);
  const double dI1 = 3.0 * K * (d11 + 2.0 * d22), dq = 2.0 * G * (d11 - d22);
  // f along the elastic trial path, alpha in [0, 1]: f = max(f+, f-) with the two linear branches
  // f_s(alpha) = s (q + alpha dq)/sqrt(3) - FSLOPE (PEAKI1 - I1 - alpha dI1). The first alpha
  // where f >= 0 is the smaller of the branches' first crossings.
  double alpha = 1.0;
  bool yields = false;
  for (double s : {1.0, -1.0}) {
    const double f0 = s * q_ / s3 - p_.limit(i1_);
    const double slope = s * dq / s3 + FS * dI1;
    const double f1 = f0 + slope;
    if (f1 <= 0.0) continue;  // this branch stays admissible over the increment
    yields = true;
    alpha = std::min(alpha, f0 >= 0.0 ? 0.0 : -f0 / slope);
  }
  if (!yields) {
    i1_ += dI1;
    q_ += dq;
    plastic_ = false;
    return;
  }
  // Elastic part up to the surface, then the linear plastic part with dl from consistency.
  const double i1e = i1_ + alpha * dI1, qe = q_ + alpha * dq;
  if (qe == 0.0) throw Error("DruckerPragerTriaxial: the path reaches the vertex (not covered)");
  const double sgn = qe > 0.0 ? 1.0 : -1.0;
  const double r11 = (1.0 - alpha) * d11, r22 = (1.0 - alpha) * d22;
  const double dl = (2.0 * G * sgn * (r11 - r22) / s3 + 3.0 * K * FS * (r11 + 2.0 * r22)) /
                    (G + 9.0 * K * p_.beta * FS * FS);
  if (dl <= 0.0) {  // round-off at the surface with a neutral increment: elastic
    i1_ += dI1;
    q_ += dq;
    plastic_ = false;
    return;
  }
  const double i1n = i1e + 3.0 * K * (r11 + 2.0 * r22) - 9.0 * K * p_.beta * FS * dl;
  const double qn = qe + 2.0 * G * (r11 - r22) - s3 * G * sgn * dl;
  if (sgn * qn <= 0.0 || !(p_.limit(i1n) > 0.0))
    throw Error("DruckerPragerTriaxial: the path reaches the vertex (not covered)");
  i1_ = i1n;
  q_ = sgn * s3 * p_.limit(i1n);  // on the surface exactly (removes round-off of the sum)
  plastic_ = true;
}

double A3Reference::z0() { return 50.0 * std::sqrt(3.0); }
double A3Reference::peak_i1() { return std::sqrt(3.0) * z0(); }
double A3Reference::fslope() { return kR0 / (std::sqrt(6.0) * z0()); }

DruckerPragerParams A3Reference::params() { return {kBulk, kShear, peak_i1(), fslope(), kBeta}; }

// Uintah AreniscaTest_02_PrescribedDeformation.inp (rows t, F11, F22 = F33).
const std::array<double, 6>& A3Reference::t() {
  static const std::array<double, 6> v{0.0, 1.0, 1.5, 2.0, 2.5, 3.0};
  return v;
}
const std::array<double, 6>& A3Reference::F11() {
  static const std::array<double, 6> v{1.0, 0.990600014, 0.973581984, 0.956856315, 0.991923945, 1.028276761};
  return v;
}
const std::array<double, 6>& A3Reference::F22() {
  static const std::array<double, 6> v{1.0, 0.990600014, 1.005903981, 1.021444382, 1.008254974, 0.995235875};
  return v;
}

// Brannon & Leelavanichkul (2010), as tabulated in AreniscaTestSuite_PostProc.py test02.
const std::array<double, 6>& A3Reference::sigma11() {
  static const double r6 = std::sqrt(6.0);
  static const std::array<double, 6> v{0.0,
                                       -850.0 / 3.0,
                                       -(50.0 / 3.0) * (9.0 + 4.0 * r6),
                                       -(50.0 / 3.0) * (9.0 + 4.0 * r6),
                                       (50.0 / 3.0) * (2.0 * r6 - 3.0),
                                       160.0 * std::sqrt(2.0 / 3.0) - 110.0};
  return v;
}
const std::array<double, 6>& A3Reference::sigma22() {
  static const double r6 = std::sqrt(6.0);
  static const std::array<double, 6> v{0.0,
                                       -850.0 / 3.0,
                                       (50.0 / 3.0) * (2.0 * r6 - 9.0),
                                       (50.0 / 3.0) * (2.0 * r6 - 9.0),
                                       -(50.0 / 3.0) * (3.0 + r6),
                                       -(10.0 / 3.0) * (33.0 + 8.0 * r6)};
  return v;
}

}  // namespace ballista
