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

#include "core/illinois.hpp"
#include "materials/geomodel_surface.hpp"

namespace ballista {

struct GeoPoint {
  double i1 = 0;      ///< effective I1 of the returned stress, Pa
  double rootj2 = 0;  ///< its sqrt(J2), Pa
};

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

/// Closest point of the surface `s` to the trial point (effective I1 `i1_t`, sqrt(J2) `rj2_t`) in
/// the space scaled by c = sqrt(3 K beta / (2 G)). The caller has checked that the trial point
/// is outside (s.f > 0). `hint_i1` (NaN: none) is the I1 of the closest point to the same trial on
/// a nearby surface (the consistency iteration moves the surface a little at a time): the search
/// first brackets the stationary point in a small interval around it, growing 8x per try, and
/// falls back to sampling the whole interval if that fails.
inline GeoPoint geo_closest_point(const GeoSurface& s, double c, double i1_t, double rj2_t,
                                  double hint_i1 = std::numeric_limits<double>::quiet_NaN()) {
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
  if (!(b0 > a0)) return {s3 * a0, s.radius(s3 * a0)};
  const double tol = 1e-13 * (std::abs(zt) + d0 + std::abs(a0) + std::abs(b0));
  auto on_surface = [&](double z) { return GeoPoint{s3 * z, s.radius(s3 * z)}; };
  const double zh = hint_i1 / s3;
  if (zh > a0 && zh < b0) {  // false for a NaN hint
    double w = 1e-3 * (b0 - a0);
    for (int k = 0; k < 4; ++k, w *= 8.0) {
      const double za = std::max(a0, zh - w), zb = std::min(b0, zh + w);
      const double fa = d.slope(za), fb = d.slope(zb);
      if (za == a0 && fa >= 0.0) return on_surface(za);
      if (zb == b0 && fb <= 0.0) return on_surface(zb);
      if (fa <= 0.0 && fb >= 0.0)
        return on_surface(illinois_root([&](double x) { return d.slope(x); }, za, fa, zb, fb, tol, 0.0));
    }
  }
  // Sample, then refine around the best sample.
  constexpr int kSamples = 12;
  const double dz = (b0 - a0) / (kSamples - 1);
  int best = 0;
  double dbest = INFINITY;
  for (int k = 0; k < kSamples; ++k) {
    const double z = k == kSamples - 1 ? b0 : a0 + k * dz;
    const double v = d.dist2(z);
    if (v < dbest) {
      dbest = v;
      best = k;
    }
  }
  const double za = best == 0 ? a0 : a0 + (best - 1) * dz;
  const double zb = best == kSamples - 1 ? b0 : std::min(b0, a0 + (best + 1) * dz);
  double fa = d.slope(za), fb = d.slope(zb);
  double z;
  if (fa >= 0.0 && best == 0)
    z = za;  // minimum at the lower end
  else if (fb <= 0.0 && best == kSamples - 1)
    z = zb;  // minimum at the upper end (the vertex, or the end of the search interval)
  else if (fa <= 0.0 && fb >= 0.0)
    z = illinois_root([&](double x) { return d.slope(x); }, za, fa, zb, fb, tol, 0.0);
  else
    z = a0 + best * dz;  // no sign change (non-smooth sample): keep the best sample
  return on_surface(z);
}

}  // namespace ballista
