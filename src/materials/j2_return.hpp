#pragma once
// Radial return for von Mises (J2) plasticity with isotropic and linear kinematic hardening and a
// flow stress that may depend on the plastic-strain increment (nonlinear hardening, strain rate),
// shared by the J2 family of models (j2_plasticity, johnson_cook); plus the composition of the
// deviatoric update with an equation of state and the algorithmic tangent of the whole step.
//
// Source: J.C. Simo & T.J.R. Hughes, Computational Inelasticity, Springer 1998, §3.3 (J2 flow
// theory), Box 3.1 (radial return with combined isotropic/kinematic hardening; closest-point
// projection, the exact backward-Euler solution for J2) and Box 3.2 (consistent tangent). Written
// in terms of the von Mises equivalent stress q = sqrt(3/2)|xi| of the relative stress
// xi = s - alpha and of the equivalent plastic strain increment Delta = sqrt(2/3)|Delta eps^p|
// (Simo & Hughes use Delta gamma = sqrt(3/2) Delta and |xi| - sqrt(2/3) K; multiplying their yield
// function by sqrt(3/2) gives the form below):
//   trial         xi_tr = s_tr - alpha_n,  q_tr = sqrt(3/2)|xi_tr|,  N = xi_tr/|xi_tr|
//   yield check   f_tr = q_tr - sigma_y(Delta = 0)
//   flow          Delta eps^p = sqrt(3/2) Delta N = (3/2) (Delta/q_tr) xi_tr
//   backstress    Delta alpha = (2/3) H_k Delta eps^p = H_k (Delta/q_tr) xi_tr  (Prager/Ziegler: the
//                 backstress law of Simo & Hughes §3.3 with their kinematic modulus H' = H_k),
//                 deviatoric by construction
//   consistency   r(Delta) = q_tr - (3G + H_k) Delta - sigma_y(Delta) = 0
//   update        s_{n+1} = s_tr - 3G (Delta/q_tr) xi_tr
// sigma_y(Delta) is the flow stress at the end of the step: sigma_y0 + H (eps_p,n + Delta) in
// closed form for linear hardening (Delta = f_tr/(3G + H_k + H), Box 3.1 step 4), otherwise any
// non-decreasing function of eps_p,n + Delta and of the rate Delta/dt (power law, Voce,
// Johnson-Cook), solved by the safeguarded Newton iteration j2_solve_increment.
//
// Consistent tangent (Box 3.2 generalised to H_k and the total slope h = d sigma_y/d Delta, which
// for a rate-dependent flow stress includes (1/dt) d sigma_y/d eps_dot):
//   d s_{n+1}/d eps = 2G theta I_dev - 2G theta_bar N (x) N,
//   theta = 1 - 3G Delta/q_tr,   theta_bar = 3G/(3G + H_k + h) - (1 - theta)
// with eps = D_bar dt, plus the pressure part of the equation of state (j2_compose_eos).
#include <cfloat>
#include <cmath>
#include <limits>
#include <vector>

#include "core/tensor.hpp"
#include "materials/eos.hpp"

namespace ballista {

/// A flow stress sigma_y and its total derivative d sigma_y / d Delta along the step, Pa.
struct FlowStress {
  double value = 0.0;
  double slope = 0.0;
};

/// Trial state and result of one radial return.
struct J2Return {
  Mat3 xi;                  ///< trial relative stress xi_tr = s_tr - alpha_n, Pa
  double q_trial = 0.0;     ///< sqrt(3/2)|xi_tr|, Pa
  double f_trial = 0.0;     ///< q_tr - sigma_y(Delta = 0), Pa
  bool plastic = false;     ///< f_trial > 0
  double delta_eqps = 0.0;  ///< Delta
  double slope = 0.0;       ///< h = d sigma_y / d Delta at the solution (for the tangent), Pa
};

/// Trial relative stress and yield check; `alpha` may be null (no kinematic hardening).
inline J2Return j2_trial(const Mat3& s_trial, const Mat3* alpha, double yield_n) {
  J2Return r;
  r.xi = alpha ? s_trial - *alpha : s_trial;
  r.q_trial = std::sqrt(1.5 * ddot(r.xi, r.xi));
  r.f_trial = r.q_trial - yield_n;
  r.plastic = r.f_trial > 0.0;  // false for a NaN trial too, which then propagates to the stress
  return r;
}

/// Solves the consistency condition q_tr - c Delta - sigma_y(Delta) = 0, c = 3G + H_k, for a flow
/// stress flow(Delta) -> FlowStress that is non-decreasing in Delta (hardening laws, rate terms;
/// temperature held at its start-of-step value). The residual is then strictly decreasing with
/// r(0) = f_tr > 0 and r(f_tr/c) = sigma_y(0) - sigma_y(f_tr/c) <= 0, so the root is bracketed in
/// (0, f_tr/c]. Newton's method starts at the upper end (where the residual is finite even for a
/// power law with n < 1 from eps_p = 0, whose slope is infinite at Delta = 0) and falls back to
/// bisection (geometric while the bracket spans decades) whenever a step leaves the bracket or the
/// slope is not finite. Stops when the residual
/// reaches round-off (8 eps q_tr) or the step is below 1e-13 Delta (Newton is quadratic near the
/// root, so the error is then ~1e-26 relative; a bisection-driven exit leaves <= 1e-13). `slope`
/// returns h at the last evaluation, i.e. at the solution to within that last step.
template <class Flow>
double j2_solve_increment(double q_trial, double f_trial, double c, const Flow& flow, double& slope) {
  double lo = 0.0, hi = f_trial / c;
  double x = hi;
  const double tol_r = 8.0 * DBL_EPSILON * q_trial;
  for (int it = 0; it < 200; ++it) {
    const FlowStress fs = flow(x);
    const double r = q_trial - c * x - fs.value;
    slope = fs.slope;
    if (std::abs(r) <= tol_r) return x;
    if (r > 0.0)
      lo = x;
    else
      hi = x;
    double xn = x + r / (c + fs.slope);  // c + slope > 0 for a non-decreasing flow stress
    if (!(xn > lo && xn < hi)) {
      // Safeguard: bisect, geometrically while the bracket spans decades (a power law with small n
      // can put the root many decades below f_tr/c, where Newton from the right always overshoots).
      if (lo == 0.0)
        xn = 1e-3 * hi;
      else
        xn = hi > 16.0 * lo ? std::sqrt(lo * hi) : 0.5 * (lo + hi);
    }
    if (std::abs(xn - x) <= 1e-13 * xn) return xn;  // slope from x: 1e-13 away, ample for a tangent
    x = xn;
  }
  return x;  // not reached: 200 bisections shrink any bracket below round-off
}

/// Applies the plastic increment r.delta_eqps: s -= 3G (Delta/q_tr) xi_tr and, if alpha is given,
/// alpha += H_k (Delta/q_tr) xi_tr. Returns Delta eps^p = (3/2)(Delta/q_tr) xi_tr.
inline Mat3 j2_apply(const J2Return& r, Mat3& s, Mat3* alpha, double G, double h_kin) {
  const double k = r.delta_eqps / r.q_trial;
  s += (-3.0 * G * k) * r.xi;
  if (alpha) *alpha += (h_kin * k) * r.xi;
  return (1.5 * k) * r.xi;
}

/// Deviatoric part of the algorithmic tangent, d s_{n+1} = a dev(d eps) + b N (N : d eps).
struct DevTangent {
  double a = 0.0;
  double b = 0.0;
  Mat3 N;  ///< unit normal xi_tr/|xi_tr| (plastic steps)
};

/// Elastic step: a = 2G.
inline DevTangent elastic_tangent(double G) { return {2.0 * G, 0.0, Mat3{}}; }

/// Plastic step (Box 3.2 generalised, see the header comment).
inline DevTangent plastic_tangent(const J2Return& r, double G, double h_kin) {
  DevTangent t;
  const double theta = 1.0 - 3.0 * G * r.delta_eqps / r.q_trial;
  const double theta_bar = 3.0 * G / (3.0 * G + h_kin + r.slope) - (1.0 - theta);
  t.a = 2.0 * G * theta;
  t.b = -2.0 * G * theta_bar;
  t.N = (std::sqrt(1.5) / r.q_trial) * r.xi;  // |xi_tr| = sqrt(2/3) q_tr
  return t;
}

/// Writes the 6x6 tangent d sigma/d eps (order 11, 22, 33, 23, 13, 12; tensor shear strains: the
/// shear column j perturbs eps_ab and eps_ba together) for d sigma = d s - I (g : d eps), where the
/// pressure varies as dp = g : d eps.
inline void j2_write_tangent(double* T, const DevTangent& t, const Mat3& g) {
  static constexpr int kA[6] = {0, 1, 2, 1, 0, 0};
  static constexpr int kB[6] = {0, 1, 2, 2, 2, 1};
  for (int j = 0; j < 6; ++j) {
    const int a = kA[j], b = kB[j];
    const bool shear = j >= 3;
    // X : E_j for a symmetric X: X_aa, or 2 X_ab for a shear column.
    const double nE = shear ? 2.0 * t.N(a, b) : t.N(a, a);
    const double gE = shear ? 2.0 * g(a, b) : g(a, a);
    for (int i = 0; i < 6; ++i) {
      const int c = kA[i], d = kB[i];
      double dev = (i == j) ? 1.0 : 0.0;  // dev(E_j)_cd
      if (!shear && i < 3) dev -= 1.0 / 3.0;
      double v = t.a * dev + t.b * t.N(c, d) * nE;
      if (i < 3) v -= gE;
      T[6 * i + j] = v;
    }
  }
}

/// Pressure update of a J2-family step and the new stress sigma = s_new - p_new I.
/// `eps` = D_bar dt, `p_old` = -tr(sigma_n)/3, `s_old`/`s_new` the deviators at t_n/t_{n+1};
/// `energy` is the EOS energy density (state field kEosEnergyField). With the linear EOS and
/// `track_energy` false the energy is neither needed nor updated (the fast path of j2_plasticity).
/// The deviatoric work over the step per reference volume is J_mid s_mid : eps with
/// J_mid = (J_n + J_{n+1})/2, s_mid = (s_n + s_{n+1})/2 (the convention of eos.hpp).
/// Fills res.tangent if non-null, with `dev` the deviatoric tangent of the step. The
/// Mie-Grüneisen pressure depends on J_{n+1}; its tangent takes the spin-free step whose midpoint
/// increment (the adapter's, materials/strain_increment.hpp) is eps, dF = (I - eps/2)^-1 (I + eps/2),
/// so J_{n+1} = J_n det(I + eps/2)/det(I - eps/2): exact for an increment without spin (the FD
/// check, and strain-driven increments).
inline Mat3 j2_compose_eos(const Eos& eos, const PointKinematics& k, const Mat3& eps, double p_old,
                           const Mat3& s_old, const Mat3& s_new, double& energy, bool track_energy,
                           const DevTangent& dev, PointResult& res) {
  double p_new;
  Mat3 g;  // dp/d eps (zero while the tension cutoff holds the pressure)
  if (eos.kind == Eos::Kind::Linear && !track_energy) {
    // p_{n+1} = p_n - K tr(eps), as eos_update (linear) without the energy bookkeeping.
    p_new = p_old - eos.bulk * trace(eps);
    if (p_new < eos.p_min) p_new = eos.p_min;
    if (res.tangent && p_new > eos.p_min) g = (-eos.bulk) * Mat3::identity();
  } else {
    const Mat3 s_mid = 0.5 * (s_old + s_new);
    const double J_mid = 0.5 * (k.J_old + k.J_new);
    const double se = ddot(s_mid, eps);
    p_new = eos_update(eos, k, p_old, energy, J_mid * se);
    if (res.tangent && p_new > eos.p_min) {
      if (eos.kind == Eos::Kind::Linear) {
        g = (-eos.bulk) * Mat3::identity();
      } else {
        // p = [A(J) + Gamma0 (E_n + W - p_n dJ/2)] / (1 + Gamma0 dJ/2), dJ = J_{n+1} - J_n (eos.hpp).
        const double eta = 1.0 - k.J_new;
        const double k0 = eos.rho0 * eos.c0 * eos.c0;
        double dpH_deta = k0;  // tension branch p_H = k0 eta
        if (eta > eos.eta_fit) dpH_deta = eos.dp_fit;  // beyond the end of the Us-up line: its tangent
        else if (eta >= 0.0) dpH_deta = eos_line_slope(eos, eta);
        // A(J) = p_H (1 - Gamma0 eta/2);  dA/dJ = -dp_H/deta (1 - Gamma0 eta/2) + Gamma0 p_H / 2.
        const double pH = eos_hugoniot_pressure(eos, k.J_new);
        const double dA = -dpH_deta * (1.0 - 0.5 * eos.gamma0 * eta) + 0.5 * eos.gamma0 * pH;
        const double den = 1.0 + 0.5 * eos.gamma0 * (k.J_new - k.J_old);
        // d J_{n+1} / d eps = J_{n+1} ((I + eps/2)^-1 + (I - eps/2)^-1)/2 (d ln det A = A^-T : dA;
        // symmetric for symmetric eps), J_{n+1} = J_n det(I + eps/2)/det(I - eps/2).
        const Mat3 Ap = Mat3::identity() + 0.5 * eps, Am = Mat3::identity() - 0.5 * eps;
        const Mat3 Jc = (0.5 * k.J_old * det(Ap) / det(Am)) * (inverse(Ap) + inverse(Am));
        // d(ds_{n+1} : eps)/d eps = Y = a dev(eps) + b (N : eps) N.
        const Mat3 Y = dev.a * deviator(eps) + (dev.b * ddot(dev.N, eps)) * dev.N;
        // dp = [(A' - Gamma0 (p_n + p_{n+1})/2) dJ + Gamma0 dW] / den,
        // dW = (s_mid : eps) dJ/2 + J_mid (Y/2 + s_mid) : d eps.
        const double cJ = dA - 0.5 * eos.gamma0 * (p_old + p_new) + 0.5 * eos.gamma0 * se;
        g = (1.0 / den) * (cJ * Jc + (eos.gamma0 * J_mid) * (0.5 * Y + s_mid));
      }
    }
  }
  if (res.tangent) j2_write_tangent(res.tangent, dev, g);
  Mat3 sigma = s_new;
  sigma(0, 0) -= p_new;
  sigma(1, 1) -= p_new;
  sigma(2, 2) -= p_new;
  return sigma;
}

/// Splits sigma into its deviator (returned) and pressure p = -tr(sigma)/3.
inline Mat3 split_pressure(const Mat3& sigma, double& p) {
  p = -trace(sigma) / 3.0;
  Mat3 s = sigma;
  s(0, 0) += p;
  s(1, 1) += p;
  s(2, 2) += p;
  return s;
}

/// Elastic deviatoric trial s_n + 2G dev(eps).
inline Mat3 deviatoric_trial(const Mat3& s_old, const Mat3& eps, double G) {
  Mat3 s = s_old + (2.0 * G) * eps;
  const double m = 2.0 * G * trace(eps) / 3.0;
  s(0, 0) -= m;
  s(1, 1) -= m;
  s(2, 2) -= m;
  return s;
}

}  // namespace ballista
