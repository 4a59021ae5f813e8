#pragma once
// Non-hardening return of the geomodel (geomodel.hpp): the closest point of a fixed yield
// surface to a trial stress in the transformed stress space of Homel, Guilkey & Brannon,
// "Numerical solution for plasticity models using consistency bisection and a transformed-space
// closest-point return: a nongradient solution method", Comput. Mech. 56 (2015) 565-584, §3-4.
//
// For an isotropic surface sqrt(J2) <= g(I1) and isotropic elasticity (K, G) the plastic
// correction sigma_trial - sigma = C : d_eps_p keeps the deviatoric direction, so the return is a
// 2-D problem in z = I1/sqrt3 (along I/sqrt3) and r = sqrt(2 J2) = |s|. With flow
// d_eps_p ~ dev(N) + beta iso(N) (N the surface normal; beta = 1 associative) the correction in
// (z, r) is -lambda (3K beta f_z, 2G f_r). Scaling r' = c r with c = sqrt(3K beta/(2G)) makes that
// correction parallel to the normal of the transformed surface (f_z, f_r/c): the return becomes
// the Euclidean closest point in (z, r') (derivation: 3K beta / 1 = 2G c / (1/c)). Homel et al.
// show this gives the exact (backward-Euler) solution for a fixed surface, vertices included.
//
// The closest point is found without gradients of the yield function at the corners: the
// distance is sampled along the surface, then the stationarity condition D'(z) = 0 is solved by
// the Illinois variant of regula falsi (core/illinois.hpp) in the bracket around the best sample. The vertex
// (PEAKI1) and the cap tip (X) are ordinary end points of the search interval.
#include <cmath>
#include <limits>
#include <numbers>

#include "core/illinois.hpp"
#include "materials/geomodel_projection.hpp"
#include "materials/geomodel_surface.hpp"

namespace ballista {

namespace geo_detail {

/// Squared distance and its derivative along the transformed surface r' = h(z) = c sqrt2 g(sqrt3 z).
struct SurfaceDistance {
  const GeoSurface& s;
  double c, zt, rt;  // transformed-space scale and trial point

  double h(double z) const { return c * std::sqrt(2.0) * s.radius(std::sqrt(3.0) * z); }
  double dist2(double z) const {
    const double dz = z - zt, dr = h(z) - rt;
    return dz * dz + dr * dr;
  }
  /// D'(z)/2 = (z - zt) + (h - rt) h'; -inf at the cap tip (h' = +inf) when rt > 0.
  double slope(double z) const {
    const double i1 = std::sqrt(3.0) * z;
    double fv, fd;
    s.limit.value_slope(i1, fv, fd);
    const double ff = std::max(0.0, fv);
    double gp, fc = 1.0;  // dg/dI1 and the cap function
    if (i1 >= s.kappa) {
      gp = fd;
    } else {
      fc = std::sqrt(s.cap2(i1));
      const double w = s.kappa - s.X;
      gp = fd * fc + (fc > 0.0 ? ff * (s.kappa - i1) / (w * w * fc) : INFINITY);
    }
    const double hz = c * std::sqrt(2.0) * ff * fc;
    if (std::isinf(gp)) return hz - rt < 0.0 ? -INFINITY : INFINITY;
    return (z - zt) + (hz - rt) * c * std::sqrt(6.0) * gp;
  }
};

}  // namespace geo_detail

/// The sampled search: closest point of the surface `s` to the trial point (effective I1 `i1_t`,
/// sqrt(J2) `rj2_t`) in the space scaled by c = sqrt(3 K beta / (2 G)), without derivatives of the
/// surface. geo_closest_point tries the certified Newton projections (geomodel_projection.hpp)
/// first and falls back to this.
///
/// The distance along the surface can have more than one local minimum: a trial point beyond a
/// thin cap (a nearly crushed rock) has one near the cap tip and one on the limit surface, where
/// the trial lies behind the face. The search therefore samples the slope D' at points dense at
/// the cap tip (uniform in the ellipse's angle on the cap, I1 = kappa - (kappa - X) cos theta) and
/// uniform on the limit surface, refines every bracket where D' goes from - to + by Illinois
/// regula falsi, adds an end of the interval where D' points outward, and keeps the nearest.
inline GeoPoint geo_closest_point_sampled(const GeoSurface& s, double c, double i1_t, double rj2_t) {
  const double s3 = std::sqrt(3.0), s2 = std::sqrt(2.0);
  const double zt = i1_t / s3, rt = c * s2 * rj2_t;
  const double zlo = s.lo() / s3, zhi = s.hi() / s3;
  // Hydrostatic trial beyond an end: the end itself.
  if (rt == 0.0) {
    if (zt >= zhi) return {s.hi(), 0.0};
    if (zt <= zlo) return {s.lo(), 0.0};
  }
  // The closest point lies within the distance d0 to a known surface point.
  double d0;
  if (zt > zhi)
    d0 = std::hypot(zt - zhi, rt);
  else if (zt < zlo)
    d0 = std::hypot(zlo - zt, rt);
  else
    d0 = rt - c * s2 * s.radius(i1_t);
  const double a0 = std::max(zlo, zt - d0), b0 = std::min(zhi, zt + d0);
  geo_detail::SurfaceDistance d{s, c, zt, rt};
  auto on_surface = [&](double z) { return GeoPoint{s3 * z, s.radius(s3 * z)}; };
  if (!(b0 > a0)) return on_surface(a0);
  const double tol = 1e-13 * (std::abs(zt) + d0 + std::abs(a0) + std::abs(b0));
  // Sample points: the interval's ends, the cap in equal steps of its ellipse angle, the limit
  // surface in equal steps of I1 (kCap + kLimit + 2 at most, sorted by construction).
  constexpr int kCap = 8, kLimit = 8;
  double z[kCap + kLimit + 2];
  int n = 0;
  z[n++] = a0;
  const double zk = std::isfinite(s.kappa) ? s.kappa / s3 : -INFINITY;
  if (zk > a0) {
    for (int j = 1; j <= kCap; ++j) {
      const double i1 = s.kappa - (s.kappa - s.X) * std::cos(0.5 * std::numbers::pi * j / kCap);
      const double zj = i1 / s3;
      if (zj > z[n - 1] && zj < b0) z[n++] = zj;
    }
  }
  const double zl = std::max(a0, zk);
  for (int j = 1; j < kLimit; ++j) {
    const double zj = zl + (b0 - zl) * j / kLimit;
    if (zj > z[n - 1] && zj < b0) z[n++] = zj;
  }
  z[n++] = b0;
  double f[kCap + kLimit + 2];
  for (int k = 0; k < n; ++k) f[k] = d.slope(z[k]);
  // Candidates: the ends if D' points out of the interval there, and each - to + bracket.
  double best_z = a0, best = INFINITY;
  auto consider = [&](double zc) {
    const double v = d.dist2(zc);
    if (v < best) {
      best = v;
      best_z = zc;
    }
  };
  if (f[0] >= 0.0) consider(a0);
  if (f[n - 1] <= 0.0) consider(b0);
  for (int k = 0; k + 1 < n; ++k)
    if (f[k] <= 0.0 && f[k + 1] >= 0.0)
      consider(illinois_root([&](double x) { return d.slope(x); }, z[k], f[k], z[k + 1], f[k + 1], tol, 0.0));
  if (!(best < INFINITY))  // no stationary point bracketed (cannot happen for a smooth D): best sample
    for (int k = 0; k < n; ++k) consider(z[k]);
  return on_surface(best_z);
}

/// Which method found a closest point (tests and benchmarks count them).
enum class GeoReturnPath { Hydrostat, Limit, Cap, Sampled };

/// Tolerance in z of the Newton projection onto the limit surface: 1e-14 of the trial's scale.
inline double geo_projection_tol(const GeoLimit& f, double c, double i1_t, double rj2_t) {
  const double scale = std::abs(i1_t) + c * rj2_t + (std::isfinite(f.peak_i1) ? std::abs(f.peak_i1) : 0.0);
  return 1e-14 * scale;
}

/// Warm starts for a sequence of nearby returns (the consistency iteration of a hardening return):
/// the piece the previous return landed on, its cap angle and its cap's branch point (a start
/// for geo_cap_kappa). Every solve is certified or globally convergent, so a hint changes the
/// iterations taken, not the answer.
struct GeoReturnHint {
  bool on_cap = false;
  double theta = std::numeric_limits<double>::quiet_NaN();
  double kappa = std::numeric_limits<double>::quiet_NaN();
};

/// Closest point of the surface `s` to the trial point (effective I1 `i1_t`, sqrt(J2) `rj2_t`) in
/// the space scaled by c = sqrt(3 K beta / (2 G)); the caller has checked that the trial point is
/// outside (s.f > 0). The certified Newton projections first (the limit surface, then the cap;
/// the cap first if the hint says the previous return landed there), the sampled search if
/// neither is certified.
inline GeoPoint geo_closest_point(const GeoSurface& s, double c, double i1_t, double rj2_t,
                                  GeoReturnPath* path = nullptr, GeoReturnHint* hint = nullptr) {
  GeoReturnPath taken = GeoReturnPath::Sampled;
  GeoPoint q;
  double theta = std::numeric_limits<double>::quiet_NaN();
  auto on_limit = [&] {
    return geo_project_on_limit(s.limit, c, i1_t, rj2_t, geo_projection_tol(s.limit, c, i1_t, rj2_t), q) &&
           !(q.i1 < s.kappa);
  };
  auto on_cap = [&] { return geo_project_on_cap(s, c, i1_t, rj2_t, q, hint ? hint->theta : theta, &theta); };
  if (rj2_t == 0.0)
    taken = GeoReturnPath::Hydrostat;
  else if (hint && hint->on_cap)
    taken = on_cap() ? GeoReturnPath::Cap : on_limit() ? GeoReturnPath::Limit : GeoReturnPath::Sampled;
  else
    taken = on_limit() ? GeoReturnPath::Limit : on_cap() ? GeoReturnPath::Cap : GeoReturnPath::Sampled;
  if (taken == GeoReturnPath::Hydrostat || taken == GeoReturnPath::Sampled)
    q = geo_closest_point_sampled(s, c, i1_t, rj2_t);
  if (path) *path = taken;
  if (hint) {
    hint->on_cap = taken == GeoReturnPath::Cap;
    if (hint->on_cap) hint->theta = theta;
  }
  return q;
}

}  // namespace ballista
