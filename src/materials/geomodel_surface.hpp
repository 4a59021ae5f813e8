#pragma once
// The yield surface, crush curve and pore-fluid laws of the sandstone geomodel (geomodel.hpp).
// Pure functions of the parameters and the plastic volumetric strain; the return algorithm
// (geomodel_return.hpp) and the verification tests use them.
//
// Sign convention: tension positive, I1 = tr(sigma), J2 = s:s/2. "Effective" quantities carry the
// pore pressure as an isotropic backstress (Homel, Guilkey & Brannon, Acta Mech. 227 (2016)
// 279-310, §2): I1' = I1 - zeta with zeta = -3 pf, i.e. I1' = I1 + 3 pf.
//
// Yield (Arenisca form; thesis seed 000 §4.1.1.3-4.1.1.4, Fig. 4.3):
//   sqrt(J2) <= Ff(I1') Fc(I1')
//   Ff(I1) = a1 - a3 exp(a2 I1) - a4 I1        limit (shear) surface, Fossum & Brannon, Kayenta
//                                               (SAND2009-2282) eq. for Ff; linear Drucker-Prager
//                                               Ff = FSLOPE (PEAKI1 - I1) is a2 = a3 = 0 and is
//                                               thesis eq. 4.2-4.4 with FSLOPE = r0/(sqrt6 z0),
//                                               PEAKI1 = sqrt3 z0.
//   Fc(I1) = sqrt(1 - ((kappa - I1)/(kappa - X))^2) for X <= I1 < kappa, 1 for I1 >= kappa
//                                               elliptical cap; its I1 radius is CR times its
//                                               sqrt(J2) radius: kappa - X = CR Ff(kappa)
//                                               (thesis Fig. 4.3; for linear Ff this is
//                                               kappa = (X + CR FSLOPE PEAKI1)/(1 + CR FSLOPE)).
// Crush curve, cap position X against plastic volumetric strain evp (thesis eq. 4.5-4.6; the
// dilatation branch is the Arenisca 3 form, whose porosity is the second line of eq. 4.5):
//   evp <= 0: X = P0 + ln(1 + evp/P3)/P1,    evp > 0: X = P0 (1 + evp)^(1/(P0 P1 P3))
//   porosity phi = 1 - exp(-(P3 + evp))       (eq. 4.6; phi0 = 1 - exp(-P3))
// Eliminating evp gives eq. 4.5 exactly: phi = 1 - exp(-P3 exp(P1 (X - P0))) in compaction.
#include <algorithm>
#include <cmath>
#include <limits>

namespace ballista {

/// Limit (shear) surface Ff(I1) = a1 - a3 exp(a2 I1) - a4 I1 (Kayenta/Arenisca form).
struct GeoLimit {
  double a1 = 0, a2 = 0, a3 = 0, a4 = 0;
  double peak_i1 = std::numeric_limits<double>::infinity();  ///< Ff(peak_i1) = 0 (inf: no vertex)

  double value(double i1) const { return a3 == 0.0 ? a1 - a4 * i1 : a1 - a3 * std::exp(a2 * i1) - a4 * i1; }
  /// dFf/dI1 (<= 0).
  double slope(double i1) const { return a3 == 0.0 ? -a4 : -a2 * a3 * std::exp(a2 * i1) - a4; }
  /// Ff and dFf/dI1 with one exponential.
  void value_slope(double i1, double& v, double& d) const {
    double d2;
    derivatives(i1, v, d, d2);
  }
  /// Bounds lo <= value(i1) <= hi without the exponential, for a yield check that needs only
  /// its sign (Geomodel::certainly_elastic). With y = a2 I1 / 8, 1 + z <= e^z (every z) and
  /// e^z <= 1/(1 - z) (z < 1) at z = y, raised to the 8th power, give
  /// (1 + y)^8 <= exp(a2 I1) <= (1 - y)^-8 for |y| < 1; the gap is about 4 y^2 relative (0.25 %
  /// at a2 I1 = -0.2). A margin of 1e-12 of the terms covers the rounding of this and of value()
  /// (a few ulps each).
  void bounds(double i1, double& lo, double& hi) const {
    if (a3 == 0.0) {
      const double v = a1 - a4 * i1;
      const double margin = 1e-12 * (std::abs(a1) + std::abs(a4 * i1));
      lo = v - margin;
      hi = v + margin;
      return;
    }
    const double y = a2 * i1 / 8.0;
    auto pow8 = [](double b) {
      const double b2 = b * b, b4 = b2 * b2;
      return b4 * b4;
    };
    const double e_hi = y < 1.0 ? 1.0 / pow8(1.0 - y) : std::numeric_limits<double>::infinity();
    const double e_lo = y > -1.0 ? pow8(1.0 + y) : 0.0;
    const double lin = a1 - a4 * i1;
    const double margin = 1e-12 * (std::abs(a1) + a3 * e_hi + std::abs(a4 * i1));
    lo = lin - a3 * e_hi - margin;
    hi = lin - a3 * e_lo + margin;
  }
  /// Ff and its first two derivatives in I1 (one exponential; Ff'' = -a2^2 a3 exp(a2 I1) <= 0).
  void derivatives(double i1, double& v, double& d1, double& d2) const {
    if (a3 == 0.0) {
      v = a1 - a4 * i1;
      d1 = -a4;
      d2 = 0.0;
      return;
    }
    const double e = a3 * std::exp(a2 * i1);
    v = a1 - e - a4 * i1;
    d1 = -a2 * e - a4;
    d2 = -a2 * a2 * e;
  }

  /// Coefficients from the user parameters (derived here from Ff(PEAKI1) = 0, -Ff'(PEAKI1) =
  /// FSLOPE, Ff -> STREN + YSLOPE |I1| as I1 -> -inf):
  ///   fslope = 0:            von Mises, Ff = stren, no vertex;
  ///   stren not given:       linear Drucker-Prager, a1 = FSLOPE PEAKI1, a4 = FSLOPE;
  ///   stren given:           a1 = STREN, a4 = YSLOPE, a2 = (FSLOPE - YSLOPE)/(STREN - YSLOPE PEAKI1),
  ///                          a3 = (STREN - YSLOPE PEAKI1) exp(-a2 PEAKI1).
  static GeoLimit make(double peak_i1, double fslope, double stren, double yslope) {
    GeoLimit f;
    if (fslope == 0.0) {
      f.a1 = stren;
      return f;
    }
    f.peak_i1 = peak_i1;
    if (std::isnan(stren)) {
      f.a1 = fslope * peak_i1;
      f.a4 = fslope;
      return f;
    }
    f.a1 = stren;
    f.a4 = yslope;
    f.a2 = (fslope - yslope) / (stren - yslope * peak_i1);
    f.a3 = (stren - yslope * peak_i1) * std::exp(-f.a2 * peak_i1);
    return f;
  }
};

/// Crush curve and porosity (thesis seed 000 eq. 4.5-4.6).
struct GeoCrushCurve {
  double p0 = 0, p1 = 0, p3 = 0;  ///< P0 (Pa, < 0), P1 (1/Pa), P3 = -ln(1 - phi0)
  bool fixed = false;             ///< cap frozen at P0 (no hardening)

  bool active() const { return p3 > 0.0; }
  /// Cap position X(evp); -inf at full crush (evp <= -P3): no porosity left, no cap.
  double cap(double evp) const {
    if (fixed || evp == 0.0) return p0;
    if (evp < 0.0) {
      const double r = 1.0 + evp / p3;
      return r > 0.0 ? p0 + std::log(r) / p1 : -std::numeric_limits<double>::infinity();
    }
    return p0 * std::pow(1.0 + evp, 1.0 / (p0 * p1 * p3));
  }
  /// dX/devp at evp, given X = cap(evp): 1/(P1 (P3 + evp)) in compaction, X / ((1 + evp) P0 P1 P3)
  /// in dilatation (the derivatives of the two branches above, equal at evp = 0); 0 for a fixed cap.
  double slope(double evp, double X) const {
    if (fixed) return 0.0;
    return evp <= 0.0 ? 1.0 / (p1 * (p3 + evp)) : X / ((1.0 + evp) * p0 * p1 * p3);
  }
  /// Porosity phi = 1 - exp(-(P3 + evp)) (eq. 4.6), clamped at 0 past full crush and, after
  /// extreme dilatation (P3 + evp > 37, where 1 - exp(-x) rounds to 1), at the largest double
  /// below 1: the porosity of a body is < 1 however far it has been torn apart.
  double porosity(double evp) const {
    return std::clamp(-std::expm1(-(p3 + evp)), 0.0, 1.0 - std::numeric_limits<double>::epsilon() / 2);
  }
  double initial_porosity() const { return -std::expm1(-p3); }
};

/// The cap's branch point kappa: kappa - X = CR Ff(kappa). g(k) = k - X - CR Ff(k) is increasing
/// (g' >= 1) and convex (Ff' <= 0, Ff'' <= 0), so Newton from a point right of the root (e.g.
/// PEAKI1, where g > 0) converges monotonically, and from a point left of it (e.g. X) its first
/// step lands right of it (a convex function lies above its tangents) and it converges
/// monotonically from there. `guess`, if
/// finite, is such a start (a nearby kappa: a sequence of returns moves the cap a little); steps
/// are kept left of PEAKI1, where g > 0, so an overshoot never reaches the exponential's overflow.
/// Stops when the step is below 1e-15 of the scale, or when the quadratic error bound of the step
/// just taken is: |k_new - kappa| <= max|g''| / (2 min g') dk^2 <= CR |Ff''| dk^2 (g' >= 1; |Ff''|
/// grows with I1 by exp(a2 dk) ~ 1 across the step, covered by the factor 2 dropped from the
/// denominator), which saves the confirming evaluation after a near start. `slope`, if given,
/// receives Ff'(kappa) at the last evaluated point (for kappa'(X) = 1/(1 - CR Ff'), where that
/// accuracy is plenty). Closed form for linear and constant Ff.
inline double geo_cap_kappa(const GeoLimit& f, double cap_ratio, double X,
                            double guess = std::numeric_limits<double>::quiet_NaN(), double* slope = nullptr) {
  if (!std::isfinite(X)) return X;
  if (f.a3 == 0.0) {  // Ff linear in I1
    if (slope) *slope = -f.a4;
    return (X + cap_ratio * f.a1) / (1.0 + cap_ratio * f.a4);
  }
  // Without a guess, start at X: g(X) = -CR Ff(X) < 0, and the first step lands on the root of the
  // tangent of g at X, which (g convex) lies right of kappa and much nearer than PEAKI1.
  double k = std::min(std::isfinite(guess) ? guess : X, f.peak_i1);
  for (int it = 0; it < 60; ++it) {
    double v, dv, d2v;
    f.derivatives(k, v, dv, d2v);
    if (slope) *slope = dv;
    const double g = k - X - cap_ratio * v;
    const double dk = g / (1.0 - cap_ratio * dv);
    k = std::min(k - dk, f.peak_i1);
    const double tol = 1e-15 * (std::abs(k) + std::abs(X));
    if (std::abs(dk) <= tol || -cap_ratio * d2v * dk * dk <= tol) break;
  }
  return k;
}

/// The whole yield surface at one state: sqrt(J2) <= g(I1') on [X, PEAKI1].
struct GeoSurface {
  GeoLimit limit;
  double X = -std::numeric_limits<double>::infinity();      ///< cap tip (effective I1)
  double kappa = -std::numeric_limits<double>::infinity();  ///< cap branch point

  double lo() const { return X; }
  double hi() const { return limit.peak_i1; }
  /// Fc^2 (cap function squared); 1 outside the cap region.
  double cap2(double i1) const {
    if (i1 >= kappa) return 1.0;
    const double u = (kappa - i1) / (kappa - X);
    return std::max(0.0, 1.0 - u * u);
  }
  /// g(I1) = Ff Fc, the largest sqrt(J2) at this I1 (0 outside [X, PEAKI1]).
  double radius(double i1) const {
    if (!(i1 >= X && i1 <= limit.peak_i1)) return 0.0;
    return std::max(0.0, limit.value(i1)) * std::sqrt(cap2(i1));
  }
  /// Yield function in stress units: sqrt(J2) - g(I1), +inf-like positive outside [X, PEAKI1].
  double f(double i1, double rootj2) const {
    if (i1 > limit.peak_i1) return rootj2 + (i1 - limit.peak_i1);
    if (i1 < X) return rootj2 + (X - i1);
    return rootj2 - radius(i1);
  }
};

/// Undrained pore pressure pf(evp) of a saturated rock whose pore volume changes by the plastic
/// volumetric strain: the matrix grains (Km) and the pore fluid (Kf) both compress under the
/// pore-pressure change dp = pf - pf0 (logarithmic, constant moduli), and together fill the
/// plastic volume (an engineering model after Homel et al. 2016, §3, solved here in closed
/// implicit form rather than integrated):
///   exp(evp) = (1 - phi0) exp(-dp/Km) + phi0 exp(-dp/Kf),   pf >= 0 (cavitation).
/// The right side is decreasing and convex in dp, so Newton from dp = -pf0 (pf = 0) converges
/// monotonically; if the left side exceeds the right at pf = 0 the fluid has cavitated. With a
/// guess `guess` >= 0 of pf (a caller that knows the fluid holds pressure, i.e. evp below the
/// cavitation strain), Newton starts there: from the right of the root its first step lands on
/// the left (the tangent of a convex function lies below it; an overshoot past pf = 0 is cut back
/// to pf = 0), then it converges monotonically.
/// `dpf_devp`, if given, receives dpf/devp = exp(evp) / (d rhs/d dp) at the last Newton iterate
/// (implicit differentiation of the saturation equation; 0 once cavitated).
inline double geo_pore_pressure(double evp, double phi0, double pf0, double Kf, double Km, double guess = -1.0,
                                double* dpf_devp = nullptr) {
  const double target = std::exp(evp);
  auto rhs = [&](double dp, double& d) {
    const double em = (1.0 - phi0) * std::exp(-dp / Km), ef = phi0 * std::exp(-dp / Kf);
    d = -em / Km - ef / Kf;
    return em + ef - target;
  };
  double dp = guess >= 0.0 ? guess - pf0 : -pf0, d = 0.0;
  if (dpf_devp) *dpf_devp = 0.0;
  if (guess < 0.0 && rhs(dp, d) <= 0.0) return 0.0;
  for (int it = 0; it < 100; ++it) {
    const double g = rhs(dp, d);
    const double step = g / d;
    // Never left of pf = 0: the root lies right of it (the fluid holds pressure), so a step from a
    // far-right guess that overshoots is cut back to a point from which Newton is monotone.
    const bool clamped = dp - step < -pf0;
    dp = std::max(dp - step, -pf0);
    // Stop at a step below the tolerance, or when the quadratic error bound of the step just taken
    // is: |dp - root| <= |rhs''| / (2 |rhs'|) step^2 <= step^2 / (2 Kf) (rhs'' = em/Km^2 + ef/Kf^2
    // <= |rhs'| / Kf for Kf < Km), which saves the confirming evaluation after a near guess.
    const double tol = 1e-14 * (std::abs(dp) + pf0) + 1e-300;
    if (std::abs(step) <= tol || (!clamped && step * step <= 2.0 * Kf * tol)) break;
  }
  if (dpf_devp && pf0 + dp > 0.0) *dpf_devp = target / d;
  return std::max(0.0, pf0 + dp);
}

/// Biot-Gassmann saturated bulk modulus (Gassmann 1951; e.g. Mavko, Mukerji & Dvorkin, The Rock
/// Physics Handbook, §6.3): K_sat = Kd + (1 - Kd/Km)^2 / (phi/Kf + (1 - phi)/Km - Kd/Km^2).
inline double biot_gassmann(double Kd, double Km, double Kf, double phi) {
  const double b = 1.0 - Kd / Km;
  const double den = phi / Kf + (1.0 - phi) / Km - Kd / (Km * Km);
  return den > 0.0 ? Kd + b * b / den : Kd;
}

}  // namespace ballista
