#pragma once
// Fast closest-point projections of the geomodel return (geomodel_return.hpp): Newton's method on
// each smooth piece of the yield surface, with a certificate that the point found is the global
// closest point. The sampled search of geomodel_return.hpp stays as the fallback when no
// certificate is obtained.
//
// Space and notation as geomodel_return.hpp: z = I1/sqrt3, r' = c sqrt2 sqrt(J2), the surface
// r' = h(z) = c sqrt2 g(sqrt3 z), g = Ff Fc. The elastic region {|r'| <= h(z)} is convex: Ff is
// concave and decreasing, Fc concave and increasing on the cap, so their product is concave
// ((Ff Fc)'' = Ff'' Fc + 2 Ff' Fc' + Ff Fc'' <= 0), and Fc' = 0 at the branch point kappa.
//
// Certificate (projection theorem onto a closed convex set, e.g. Bertsekas, Convex Analysis and
// Optimization, 2003, Prop. 2.2.1): a boundary point q is the projection of an outside point p iff
// p - q lies in the normal cone at q. On a smooth piece that is: q stationary for |p - q|^2 along
// the surface AND p on the outer side of the tangent line, (p - q) . n > 0 with n the outward
// normal. The projection is unique, so a certified Newton root is exactly the point the sampled
// search converges to (to the tolerances of the two root finders).
//
// Pieces:
//  - the limit surface alone, r' = c sqrt2 Ff(sqrt3 z) for z <= PEAKI1/sqrt3 (no cap): its set is
//    convex and contains the capped set, so its projection, if it lies right of kappa (on the
//    capped surface too), is the capped set's projection (a projection onto a superset that lies
//    in the subset is the projection onto the subset). For a trial outside it the stationarity
//    function F(z) = (z - zt) + (h - rt) h' is negative left of its single root and increasing
//    from there (F' = 1 + h'^2 + (h - rt) h'' >= 1 where h <= rt, h'' <= 0), so a bracketed
//    Newton iteration converges to the unique root; the vertex is the answer when the trial lies in
//    its normal cone (rt s <= zt - zhi, s = -h'(zhi)).
//  - the cap, parametrised by its ellipse angle theta: I1 = kappa - (kappa - X) cos theta,
//    g = Ff(I1) sin theta, theta in [0, pi/2]. theta is smooth at the cap tip, where h'(z) is
//    infinite. F(theta) = (q - p) . q' is negative at the tip for rt > 0; when it is positive at
//    kappa the cap holds a stationary point, found by bracketed Newton and then certified.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "materials/geomodel_surface.hpp"

namespace ballista {

struct GeoPoint {
  double i1 = 0;      ///< effective I1 of the returned stress, Pa
  double rootj2 = 0;  ///< its sqrt(J2), Pa
};

namespace geo_detail {

/// Newton's method for a root of F on [lo, hi] with F(lo) <= 0 <= F(hi) (not evaluated), kept in
/// the bracket by bisection when a step leaves it or F' <= 0. `eval(t, F, dF)` evaluates at t and
/// records what the caller needs of that point. Returns true when a step shorter than `tol` was
/// taken; the root is then the last evaluated point, within tol.
template <class Eval>
bool bracketed_newton(Eval&& eval, double lo, double hi, double t, double tol, double& root, int max_it = 60) {
  for (int it = 0; it < max_it; ++it) {
    double F, dF;
    eval(t, F, dF);
    root = t;
    if (F == 0.0) return true;
    const double step = F / dF;
    if (dF > 0.0 && std::abs(step) <= tol) return true;  // (before the bracket test: a step below
                                                          // the spacing of doubles rounds to t)
    (F > 0.0 ? hi : lo) = t;
    double next = t - step;
    if (!(dF > 0.0) || !(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (!(hi - lo > tol)) return true;
    t = next;
  }
  return false;
}

}  // namespace geo_detail

/// Projection of the trial (effective I1 `i1_t`, sqrt(J2) `rj2_t` > 0) onto the limit surface
/// alone, in the space scaled by c (see above). Returns false if the trial lies inside the limit
/// surface (then it is outside only because of the cap) or Newton failed; `tol` is in z.
/// `ff_t`, if not NaN, is f.value(i1_t), known to the caller (its exponential saved).
inline bool geo_project_on_limit(const GeoLimit& f, double c, double i1_t, double rj2_t, double tol, GeoPoint& q,
                                 double ff_t = std::numeric_limits<double>::quiet_NaN()) {
  const double s3 = std::sqrt(3.0), k = c * std::sqrt(2.0);  // r' = k sqrt(J2)
  const double zt = i1_t / s3, rt = k * rj2_t;
  const double zhi = f.peak_i1 / s3;  // +inf without a vertex
  double d0;                          // distance to a known point of the surface
  if (zt <= zhi) {
    const double ht = k * (std::isnan(ff_t) ? f.value(i1_t) : ff_t);
    if (!(rt > ht)) return false;  // inside the limit surface
    d0 = rt - ht;
  } else {
    double v, d;
    f.value_slope(f.peak_i1, v, d);
    // Vertex: the trial lies in its normal cone, spanned by (s, +-1) with s = -h'(zhi) = -k sqrt3 Ff'.
    if (rt * (-k * s3 * d) <= zt - zhi) {
      q = {f.peak_i1, 0.0};
      return true;
    }
    d0 = std::hypot(zt - zhi, rt);
  }
  double ff = 0.0;
  auto eval = [&](double z, double& F, double& dF) {
    double v, d1, d2;
    f.derivatives(s3 * z, v, d1, d2);
    const double h = k * v, hp = k * s3 * d1, hpp = 3.0 * k * d2;
    F = (z - zt) + (h - rt) * hp;
    dF = 1.0 + hp * hp + (h - rt) * hpp;
    ff = v;
  };
  const double lo = zt - d0, hi = std::min(zhi, zt + d0);
  double z;
  if (!geo_detail::bracketed_newton(eval, lo, hi, std::clamp(zt, lo, hi), tol, z)) return false;
  q = {s3 * z, std::max(0.0, ff)};
  return true;
}

/// Projection onto the cap piece (I1 in [X, kappa]) of `s`, certified to be the projection onto
/// the whole surface; false if the cap holds no certified stationary point (the caller falls back).
/// `th_start`, if finite, is the angle Newton starts from (a nearby return's `th_out`).
inline bool geo_project_on_cap(const GeoSurface& s, double c, double i1_t, double rj2_t, GeoPoint& q,
                               double th_start = std::numeric_limits<double>::quiet_NaN(),
                               double* th_out = nullptr) {
  if (!(std::isfinite(s.X) && s.kappa > s.X) || !(rj2_t > 0.0)) return false;
  const double s3 = std::sqrt(3.0), k = c * std::sqrt(2.0);
  const double zt = i1_t / s3, rt = k * rj2_t, w = s.kappa - s.X;
  double z = 0, r = 0, zp = 0, rp = 0, ff = 0, sn = 0;
  auto eval = [&](double th, double& F, double& dF) {
    sn = std::sin(th);
    const double cs = std::cos(th);
    const double i1 = s.kappa - w * cs, i1p = w * sn, i1pp = w * cs;
    double v, d1, d2;
    s.limit.derivatives(i1, v, d1, d2);
    const double fp = d1 * i1p, fpp = d2 * i1p * i1p + d1 * i1pp;  // dFf/dtheta, d2Ff/dtheta2
    const double g = v * sn, gp = fp * sn + v * cs, gpp = fpp * sn + 2.0 * fp * cs - v * sn;
    z = i1 / s3;
    zp = i1p / s3;
    const double zpp = i1pp / s3;
    r = k * g;
    rp = k * gp;
    const double rpp = k * gpp;
    F = (z - zt) * zp + (r - rt) * rp;
    dF = zp * zp + rp * rp + (z - zt) * zpp + (r - rt) * rpp;
    ff = v;
  };
  const double half_pi = 0.5 * std::numbers::pi;
  // Newton from th0 in [a, b] (a bracket F(a) < 0 < F(b) when `bracketed`), then the certificate:
  // (p - q) . n > 0 with the outward normal n = (-r', z').
  auto solve = [&](double a, double b, double th0, int max_it, GeoPoint& out) {
    double th;
    if (!geo_detail::bracketed_newton(eval, a, b, th0, 1e-14, th, max_it)) return false;
    if (!((zt - z) * -rp + (rt - r) * zp > 0.0)) return false;
    out = {s3 * z, std::max(0.0, ff) * sn};
    if (th_out) *th_out = th;
    return true;
  };
  // A warm start (a nearby return landed on the cap at th_start): a few Newton steps from there,
  // with no bracket evaluated; the certificate decides, as for any other start.
  if (std::isfinite(th_start) && th_start > 0.0 && th_start < half_pi && solve(0.0, half_pi, th_start, 8, q))
    return true;
  // The projection lies within the distance d0 of the trial to a known surface point (the cap tip,
  // or the point below the trial), so at I1 <= i1_t + sqrt3 d0: theta <= th_hi. Searching there
  // only also skips a local minimum on the far side of the cap (a trial beyond the cap tip).
  double d0 = std::hypot(zt - s.X / s3, rt);
  if (i1_t >= s.X && i1_t <= s.kappa) d0 = std::min(d0, rt - k * s.radius(i1_t));
  const double cos_hi = (s.kappa - i1_t - s3 * d0) / w;
  const double th_hi = cos_hi <= 0.0 ? half_pi : cos_hi >= 1.0 ? 0.0 : std::acos(cos_hi);
  // Start at the trial's angle in the ellipse scaled to unit half-axes.
  const double th_trial = std::atan2(rj2_t / s.limit.value(s.kappa), (s.kappa - i1_t) / w);
  auto solve_in = [&](double a, double b, GeoPoint& out) {
    return solve(a, b, std::clamp(th_trial, a + 1e-3 * (b - a), b - 1e-3 * (b - a)), 60, out);
  };
  double F, dF;
  eval(th_hi, F, dF);
  if (F > 0.0) return solve_in(0.0, th_hi, q);
  // F < 0 at both ends: the distance has a local maximum on the way (a trial beyond the tip of a
  // thin cap, across from its far side). Walk from the tip to the first bracket, and on.
  constexpr int kWalk = 8;
  double a = 0.0;
  for (int j = 1; j < kWalk; ++j) {
    const double b = th_hi * j / kWalk;
    eval(b, F, dF);
    if (F > 0.0 && solve_in(a, b, q)) return true;
    if (!(F > 0.0)) a = b;
  }
  return false;
}

}  // namespace ballista
