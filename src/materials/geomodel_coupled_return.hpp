#pragma once
// The hardening return of the geomodel solved as one Newton system: the returned point on one
// smooth piece of the yield surface and the plastic volumetric strain increment d together,
// instead of the consistency iteration (Homel et al. 2015 §5, Geomodel::consistent_increment)
// around full closest-point returns. Space and parametrisations as geomodel_projection.hpp.
//
// Two equations, with e = evp + d, the pore pressure pf(e) (0 drained) shifting the trial in
// effective stress (I1' = I1 + 3 pf, geomodel_surface.hpp) and X(e) the crush curve moving the cap:
//   R1 = (q - p(e)) . q' = 0              the returned point q is stationary on the surface of e
//                                          for the effective trial p(e) = (I1_t + 3 pf(e), rj2_t);
//   R2 = (I1_t - I1(q) + 3 pf(e))/(3K) - d = 0   its plastic volume change is d (d_eps_p =
//                                          C^-1 : (sigma_trial - sigma), volumetric part).
// On the cap the point is its ellipse angle theta: I1 = kappa - (kappa - X) cos theta, with
// kappa(X) the branch point (kappa - X = CR Ff(kappa), so kappa'(X) = 1/(1 - CR Ff'(kappa))); on
// the limit surface it is z = I1/sqrt3 (the limit surface does not move with X; only pf moves the
// trial). The Jacobian is exact up to kappa'(X) and dpf/de, taken at the last iterate of their own
// solves (which only affects the rate).
//
// A converged point is certified as the consistency iteration's answer would be: stationary with
// the trial on the outer side of the tangent, so the projection onto the convex surface of e
// (geomodel_projection.hpp), on its piece of that surface, with its increment satisfying R2 to the
// caller's tolerance. Anything else (the point leaving its piece, a step past full crush, no
// convergence in 20 steps) reports failure and the caller runs the consistency iteration.
#include <cmath>
#include <numbers>

#include "materials/geomodel_projection.hpp"
#include "materials/geomodel_surface.hpp"

namespace ballista {

/// What both pieces need: the surface laws, the trial (total I1, sqrt(J2)), the state and moduli.
/// `pore(e, guess, dpf)` returns pf(e) (guess: a nearby value, or < 0: none) and sets dpf = dpf/de.
template <class Pore>
struct GeoCoupledProblem {
  const GeoLimit& f;
  double cap_ratio;
  const GeoCrushCurve& crush;
  Pore pore;
  double evp, c, K, I1_t, rj2_t;
  double pf_guess = -1.0;  ///< a nearby pore pressure (that of evp) to start from, or < 0
};

struct GeoCoupledResult {
  double d = 0;   ///< plastic volumetric strain increment
  GeoPoint q;     ///< returned point (effective I1, sqrt(J2)) on the surface of evp + d
  double pf = 0;  ///< pore pressure at evp + d
};

/// Return onto the cap, from angle `theta0` and d = 0; `kappa0` starts the branch-point solves.
/// Converged when the Newton step in theta is below 1e-14 and that in d below `d_tol(d)`.
template <class Pore, class Tol>
bool geo_cap_coupled_return(const GeoCoupledProblem<Pore>& P, double theta0, double kappa0, Tol&& d_tol,
                            GeoCoupledResult& out) {
  if (!(P.rj2_t > 0.0) || !P.crush.active()) return false;
  const double s3 = std::sqrt(3.0), k = P.c * std::sqrt(2.0);
  const double rt = k * P.rj2_t, K3 = 3.0 * P.K;
  const double half_pi = 0.5 * std::numbers::pi;
  double th = theta0, d = 0.0, kappa = kappa0, dkappa_dX = 0.0, X_prev = 0.0, pf = -1.0, dpf = 0.0, e_prev = 0.0;
  for (int it = 0; it < 20; ++it) {
    const double e = P.evp + d;
    if (!(P.crush.p3 + e > 0.0)) return false;  // past full crush: no cap
    const double X = P.crush.cap(e), dX = P.crush.slope(e, X);
    // pf from the previous one moved along its tangent (then its solve ends early too).
    pf = P.pore(e, it == 0 ? P.pf_guess : std::max(0.0, pf + dpf * (e - e_prev)), dpf);
    e_prev = e;
    const double zt = (P.I1_t + 3.0 * pf) / s3;
    // kappa from the previous one moved along its tangent: the solve then typically ends after one
    // evaluation by its error bound (geo_cap_kappa).
    double slope_k = 0.0;
    kappa = geo_cap_kappa(P.f, P.cap_ratio, X, it == 0 ? kappa : kappa + dkappa_dX * (X - X_prev), &slope_k);
    const double w = kappa - X;
    if (!(w > 0.0) || !std::isfinite(dX)) return false;
    const double dk = 1.0 / (1.0 - P.cap_ratio * slope_k);  // dkappa/dX
    const double dw = dk - 1.0;
    dkappa_dX = dk;
    X_prev = X;
    const double sn = std::sin(th), cs = std::cos(th);
    // I1 and its derivatives: theta (p), theta twice (pp), X (_x).
    const double i1 = kappa - w * cs, i1p = w * sn, i1pp = w * cs;
    const double i1_x = dk - dw * cs, i1p_x = dw * sn;
    double v, d1, d2;
    P.f.derivatives(i1, v, d1, d2);
    const double fp = d1 * i1p, fpp = d2 * i1p * i1p + d1 * i1pp;  // dFf/dtheta, d2Ff/dtheta2
    const double v_x = d1 * i1_x, fp_x = d2 * i1_x * i1p + d1 * i1p_x;
    const double z = i1 / s3, zp = i1p / s3, zpp = i1pp / s3, z_x = i1_x / s3, zp_x = i1p_x / s3;
    const double r = k * v * sn, rp = k * (fp * sn + v * cs), rpp = k * (fpp * sn + 2.0 * fp * cs - v * sn);
    const double r_x = k * v_x * sn, rp_x = k * (fp_x * sn + v_x * cs);
    // Residuals and the Jacobian (dzt/dd = sqrt3 dpf/de).
    const double R1 = (z - zt) * zp + (r - rt) * rp;
    const double R2 = (P.I1_t - i1 + 3.0 * pf) / K3 - d;
    const double J11 = zp * zp + rp * rp + (z - zt) * zpp + (r - rt) * rpp;
    const double J12 = (z_x * zp + (z - zt) * zp_x + r_x * rp + (r - rt) * rp_x) * dX - s3 * dpf * zp;
    const double J21 = -i1p / K3;
    const double J22 = (-i1_x * dX + 3.0 * dpf) / K3 - 1.0;
    const double det = J11 * J22 - J12 * J21;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
    const double dth = (-R1 * J22 + R2 * J12) / det;
    const double dd = (-R2 * J11 + R1 * J21) / det;
    if (std::abs(dth) <= 1e-14 && std::abs(dd) <= d_tol(d)) {
      // Converged at the evaluated point: certify it as the projection onto its own surface.
      if (!(J11 > 0.0) || !((zt - z) * -rp + (rt - r) * zp > 0.0)) return false;
      out.d = d;
      out.q = {i1, std::max(0.0, v) * sn};
      out.pf = pf;
      return true;
    }
    th += dth;
    d += dd;
    if (!(th > 0.0 && th < half_pi)) return false;  // off the cap: the caller's iteration decides
  }
  return false;
}

/// Return onto the limit surface (the part right of the cap's branch point), from z0 and d = 0.
/// Converged when the Newton step in z is below `z_tol` and that in d below `d_tol(d)`.
template <class Pore, class Tol>
bool geo_limit_coupled_return(const GeoCoupledProblem<Pore>& P, double z0, double z_tol, Tol&& d_tol,
                              GeoCoupledResult& out) {
  if (!(P.rj2_t > 0.0)) return false;
  const double s3 = std::sqrt(3.0), k = P.c * std::sqrt(2.0);
  const double rt = k * P.rj2_t, K3 = 3.0 * P.K;
  const double zhi = P.f.peak_i1 / s3;
  double z = z0, d = 0.0, pf = -1.0, dpf = 0.0, e_prev = 0.0;
  for (int it = 0; it < 20; ++it) {
    const double e = P.evp + d;
    pf = P.pore(e, it == 0 ? P.pf_guess : std::max(0.0, pf + dpf * (e - e_prev)), dpf);
    e_prev = e;
    const double zt = (P.I1_t + 3.0 * pf) / s3;
    double v, d1, d2;
    P.f.derivatives(s3 * z, v, d1, d2);
    const double h = k * v, hp = k * s3 * d1, hpp = 3.0 * k * d2;
    const double R1 = (z - zt) + (h - rt) * hp;
    const double R2 = (P.I1_t - s3 * z + 3.0 * pf) / K3 - d;
    const double J11 = 1.0 + hp * hp + (h - rt) * hpp;
    const double J12 = -s3 * dpf;
    const double J21 = -s3 / K3;
    const double J22 = 3.0 * dpf / K3 - 1.0;
    const double det = J11 * J22 - J12 * J21;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
    const double dz = (-R1 * J22 + R2 * J12) / det;
    const double dd = (-R2 * J11 + R1 * J21) / det;
    if (std::abs(dz) <= z_tol && std::abs(dd) <= d_tol(d)) {
      // Certificate: stationary, trial above the surface (outward side of the tangent), and the
      // point right of the cap's branch point of the surface of e (I1 - X >= CR Ff).
      const double X = P.crush.active() ? P.crush.cap(e) : -INFINITY;
      if (!(J11 > 0.0) || !(rt - h > 0.0) || !(s3 * z - X >= P.cap_ratio * v)) return false;
      out.d = d;
      out.q = {s3 * z, std::max(0.0, v)};
      out.pf = pf;
      return true;
    }
    z += dz;
    d += dd;
    if (!(z < zhi)) return false;  // at the vertex: the caller's iteration decides
  }
  return false;
}

}  // namespace ballista
