// The reference of uniaxial_strain_cap.hpp: the surface, the yield point and the integrated ODE.
#include "verify/uniaxial_strain_cap.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace ballista {

CapSurfaceValue cap_surface(const CapSurfaceParams& p, double i1, double X) {
  CapSurfaceValue v;
  const double fs = p.fslope, cr = p.cap_ratio;
  const double ff = fs * (p.peak_i1 - i1);
  const double kappa = (X + cr * fs * p.peak_i1) / (1.0 + cr * fs);
  if (i1 >= kappa) {
    v.g = ff;
    v.g_i1 = -fs;
    return v;
  }
  const double w = kappa - X, u = (kappa - i1) / w, fc = std::sqrt(std::max(0.0, 1.0 - u * u));
  const double dkappa = 1.0 / (1.0 + cr * fs);
  const double du_di1 = -1.0 / w;
  const double du_dx = (dkappa * w - (kappa - i1) * (dkappa - 1.0)) / (w * w);
  const double dfc_du = -u / fc;
  v.g = ff * fc;
  v.g_i1 = -fs * fc + ff * dfc_du * du_di1;
  v.g_x = ff * dfc_du * du_dx;
  return v;
}

double UniaxialStrainCap::cap_of(double evp) const { return p_.fixed_cap ? p_.curve.p0 : p_.curve.cap(evp); }

double UniaxialStrainCap::cap_slope(double evp) const {
  if (p_.fixed_cap) return 0.0;
  const CrushCurve& c = p_.curve;
  // The derivatives of the two branches of CrushCurve::cap (hydrostatic_crush.cpp).
  if (evp <= 0.0) return 1.0 / (c.p1 * (c.p3 + evp));
  return c.cap(evp) / ((1.0 + evp) * c.p0 * c.p1 * c.p3);
}

UniaxialStrainCap::UniaxialStrainCap(const CapSurfaceParams& p, double e_max, int grid_steps) : p_(p) {
  const double K = p.bulk, G = p.shear, qe = 2.0 * G / std::sqrt(3.0);
  // Yield: the elastic line (I1, q) = (-3K e, qe e) meets g(I1, P0); q - g grows along it.
  auto excess = [&](double e) { return qe * e - cap_surface(p, -3.0 * K * e, p.curve.p0).g; };
  if (excess(e_max) <= 0.0) throw Error("uniaxial strain with a cap: no yield up to e_max");
  double lo = 0.0, hi = e_max;
  for (int it = 0; it < 200 && hi - lo > 1e-16 * e_max; ++it) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) > 0.0 ? hi : lo) = mid;
  }
  e_yield_ = 0.5 * (lo + hi);
  h_ = (e_max - e_yield_) / grid_steps;
  // d(I1, evp)/de on the surface (header comment).
  auto rate = [&](double i1, double evp, double& di1, double& devp) {
    const CapSurfaceValue s = cap_surface(p, i1, cap_of(evp));
    const double dl = (qe + 3.0 * K * s.g_i1) / (G + 9.0 * K * s.g_i1 * s.g_i1 - 3.0 * s.g_x * cap_slope(evp) * s.g_i1);
    devp = -3.0 * s.g_i1 * dl;
    di1 = -3.0 * K * (1.0 + devp);
  };
  double i1 = -3.0 * K * e_yield_, evp = 0.0;
  auto store = [&] {
    double di1, devp;
    rate(i1, evp, di1, devp);
    i1_.push_back(i1);
    evp_.push_back(evp);
    di1_.push_back(di1);
    devp_.push_back(devp);
  };
  store();
  for (int k = 0; k < grid_steps; ++k) {
    double a1 = di1_.back(), b1 = devp_.back(), a2, b2, a3, b3, a4, b4;
    rate(i1 + 0.5 * h_ * a1, evp + 0.5 * h_ * b1, a2, b2);
    rate(i1 + 0.5 * h_ * a2, evp + 0.5 * h_ * b2, a3, b3);
    rate(i1 + h_ * a3, evp + h_ * b3, a4, b4);
    i1 += h_ / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    evp += h_ / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4);
    store();
  }
}

double UniaxialStrainCap::interpolate(const std::vector<double>& y, const std::vector<double>& dy, double e) const {
  // Cubic Hermite on the grid's values and rates: O(h^4), below the RK4 error.
  const double x = (e - e_yield_) / h_;
  const size_t k = std::min(static_cast<size_t>(std::max(0.0, std::floor(x))), y.size() - 2);
  const double w = x - static_cast<double>(k), w2 = w * w, w3 = w2 * w;
  return (2 * w3 - 3 * w2 + 1) * y[k] + (w3 - 2 * w2 + w) * h_ * dy[k] + (-2 * w3 + 3 * w2) * y[k + 1] +
         (w3 - w2) * h_ * dy[k + 1];
}

double UniaxialStrainCap::i1(double e) const {
  return e <= e_yield_ ? -3.0 * p_.bulk * e : interpolate(i1_, di1_, e);
}

double UniaxialStrainCap::evp(double e) const { return e <= e_yield_ ? 0.0 : interpolate(evp_, devp_, e); }

double UniaxialStrainCap::cap(double e) const { return cap_of(evp(e)); }

double UniaxialStrainCap::q(double e) const {
  if (e <= e_yield_) return 2.0 * p_.shear / std::sqrt(3.0) * e;
  return cap_surface(p_, i1(e), cap(e)).g;
}

double UniaxialStrainCap::stationary_i1() const {
  // g_I falls monotonically over the cap (g is concave there) from +inf at X to -FSLOPE at kappa.
  const double X = p_.curve.p0, target = 0.5 / std::sqrt(3.0);
  double lo = X, hi = (X + p_.cap_ratio * p_.fslope * p_.peak_i1) / (1.0 + p_.cap_ratio * p_.fslope);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (cap_surface(p_, mid, X).g_i1 > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace ballista
