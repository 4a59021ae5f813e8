// Crush curve, porosity and the exact hydrostatic response (see hydrostatic_crush.hpp).
#include "verify/hydrostatic_crush.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace ballista {

// Arenisca3 crush curve (geomodel contract; thesis seed 000 eq. 4.5 inverted).
double CrushCurve::cap(double evp) const {
  if (evp <= 0.0) return p0 + std::log1p(evp / p3) / p1;
  return p0 * std::pow(1.0 + evp, 1.0 / (p0 * p1 * p3));
}

double CrushCurve::evp_at_cap(double x) const {
  if (x <= p0) return p3 * std::expm1(p1 * (x - p0));
  return std::pow(x / p0, p0 * p1 * p3) - 1.0;
}

// Thesis seed 000 eq. 4.6.
double CrushCurve::porosity(double evp) const { return -std::expm1(-(p3 + evp)); }

// Thesis seed 000 eq. 4.5 (both branches; the dilatation one with the power of the crush curve).
double CrushCurve::porosity_at_cap(double i1) const {
  if (i1 < p0) return -std::expm1(-p3 * std::exp(p1 * (i1 - p0)));
  return -std::expm1(1.0 - std::pow(i1 / p0, p0 * p1 * p3) - p3);
}

double CrushCurve::initial_porosity() const { return -std::expm1(-p3); }

double solve_compaction(const CrushCurve& c, double bulk, double ev, double evp_hi) {
  auto g = [&](double e) { return e + c.cap(e) / (3.0 * bulk) - ev; };
  if (g(evp_hi) < 0.0)
    throw Error(fmt::format("solve_compaction: ev = {:g} lies above the cap at evp = {:g}", ev, evp_hi));
  // g -> -inf as evp -> -P3: halve the distance to -P3 until g < 0 (a bracket), then bisect.
  double hi = evp_hi, lo = evp_hi;
  for (int k = 0; k < 2000 && g(lo) >= 0.0; ++k) lo = -c.p3 + 0.5 * (lo + c.p3);
  if (g(lo) >= 0.0) throw Error("solve_compaction: no bracket (ev beyond full crush)");
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;  // interval at round-off
    (g(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

HydrostaticCap::HydrostaticCap(const HydroCapParams& p) : p_(p) {
  const CrushCurve& c = p.curve;
  if (!(p.bulk > 0.0) || !(p.peak_i1 > 0.0) || !(c.p0 < 0.0) || !(c.p1 > 0.0) || !(c.p3 > 0.0))
    throw Error("HydrostaticCap: need bulk > 0, peak_i1 > 0, p0 < 0, p1 > 0, p3 > 0");
}

double HydrostaticCap::cap() const { return p_.fixed_cap ? p_.curve.p0 : p_.curve.cap(evp_); }

void HydrostaticCap::advance_to(double ev) {
  const double K3 = 3.0 * p_.bulk;
  const double trial = K3 * (ev - evp_);
  if (trial > p_.peak_i1) {
    evp_ = ev - p_.peak_i1 / K3;
    i1_ = p_.peak_i1;
    phase_ = HydroPhase::Dilatation;
  } else if (trial < cap()) {
    if (p_.fixed_cap) {
      evp_ = ev - p_.curve.p0 / K3;
    } else {
      evp_ = solve_compaction(p_.curve, p_.bulk, ev, evp_);
    }
    i1_ = cap();
    phase_ = HydroPhase::Compaction;
  } else {
    i1_ = trial;
    phase_ = HydroPhase::Elastic;
  }
  ev_ = ev;
}

}  // namespace ballista
