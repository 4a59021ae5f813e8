#include "verify/hydrostatic_compare.hpp"

#include <algorithm>
#include <cmath>

#include "verify/geo_hooks.hpp"

namespace ballista {

double GeoSandstone::p3() const { return -std::log1p(-phi0); }

std::vector<std::pair<std::string, double>> GeoSandstone::scalars() const {
  return {{"p0", p0}, {"p1", p1}, {"p3", p3()}, {"peak_i1", peak_i1}, {"bulk", bulk}, {"phi0", phi0}};
}

void GeoSandstone::add_crush_curve(VerifyCase& c, double i1_from, double i1_to, int n) const {
  std::vector<double> ci1, cphi;
  for (int k = 0; k <= n; ++k) {
    const double x = i1_from + (i1_to - i1_from) * k / n;
    ci1.push_back(x);
    cphi.push_back(curve().porosity_at_cap(x));
  }
  c.series.push_back({"curve_i1", ci1});
  c.series.push_back({"curve_porosity", cphi});
}

GeoReduction GeoSandstone::reduction(bool fixed_cap, double fluid_bulk) const {
  GeoReduction g;
  g.density = density;
  g.bulk = bulk;
  g.shear = shear;
  g.peak_i1 = peak_i1;
  g.fslope = fslope;
  g.cap_ratio = cap_ratio;
  g.p0 = p0;
  g.p1 = p1;
  g.p3 = p3();
  g.fixed_cap = fixed_cap;
  g.fluid_bulk = fluid_bulk;
  g.pore_pressure0 = 0.0;
  return g;
}

HydroComparison compare_hydrostatic(const DriveResult& r, const HydroCapParams& p, const std::vector<double>& row_t) {
  HydroComparison c;
  const int i_evp = state_index(r, "plastic_volumetric_strain");
  const int i_phi = state_index(r, "porosity");
  if (i_evp < 0) c.missing += "plastic_volumetric_strain ";
  if (i_phi < 0) c.missing += "porosity ";
  HydrostaticCap exact(p);
  const size_t nlegs = row_t.size() - 1;
  c.leg_i1_error.assign(nlegs, 0.0);
  c.leg_i1_scale.assign(nlegs, 0.0);
  std::vector<double> leg_abs(nlegs, 0.0);
  double max_i1 = 0.0, cap_abs = 0.0, shear = 0.0;
  for (size_t k = 0; k < r.records.size(); ++k) {
    const DriveRecord& rec = r.records[k];
    const double ev = std::log(rec.F(0, 0)) + std::log(rec.F(1, 1)) + std::log(rec.F(2, 2));
    exact.advance_to(ev);
    int leg = 1;
    while (leg < static_cast<int>(nlegs) && rec.t > row_t[static_cast<size_t>(leg)] + 1e-12) ++leg;
    const double i1 = trace(rec.sigma);
    const Mat3 d = deviator(rec.sigma);
    const double evp = i_evp >= 0 ? rec.state[static_cast<size_t>(i_evp)] : std::nan("");
    const double phi = i_phi >= 0 ? rec.state[static_cast<size_t>(i_phi)] : std::nan("");
    c.t.push_back(rec.t);
    c.ev.push_back(ev);
    c.i1.push_back(i1);
    c.i1_an.push_back(exact.i1());
    c.evp.push_back(evp);
    c.evp_an.push_back(exact.evp());
    c.phi.push_back(phi);
    c.phi_an.push_back(exact.porosity());
    c.sqrt_j2.push_back(std::sqrt(0.5 * ddot(d, d)));
    c.leg.push_back(leg);
    const bool compacting = exact.phase() == HydroPhase::Compaction;
    c.compaction.push_back(compacting ? 1 : 0);
    const size_t l = static_cast<size_t>(leg - 1);
    leg_abs[l] = std::max(leg_abs[l], std::abs(i1 - exact.i1()));
    c.leg_i1_scale[l] = std::max(c.leg_i1_scale[l], std::abs(exact.i1()));
    max_i1 = std::max(max_i1, std::abs(exact.i1()));
    shear = std::max(shear, c.sqrt_j2.back());
    if (i_evp >= 0) c.max_evp_error = std::max(c.max_evp_error, std::abs(evp - exact.evp()));
    // Porosity from the first update on: records[0] holds the state fields' static initial values
    // (StateFieldSpec::initial cannot depend on P3), which a model may overwrite only when it runs.
    if (i_phi >= 0 && k > 0) c.max_phi_error = std::max(c.max_phi_error, std::abs(phi - exact.porosity()));
    if (i_evp >= 0 && i_phi >= 0 && k > 0)
      c.phi_identity = std::max(c.phi_identity, std::abs(phi - p.curve.porosity(evp)));
    if (i_evp >= 0 && compacting && k > 0) {
      const double x = p.fixed_cap ? p.curve.p0 : p.curve.cap(evp);
      cap_abs = std::max(cap_abs, std::abs(i1 - x));
    }
  }
  for (size_t l = 0; l < nlegs; ++l) {
    c.leg_i1_error[l] = c.leg_i1_scale[l] > 0.0 ? leg_abs[l] / c.leg_i1_scale[l] : leg_abs[l];
    c.max_i1_error = std::max(c.max_i1_error, c.leg_i1_error[l]);
  }
  c.cap_consistency = max_i1 > 0.0 ? cap_abs / max_i1 : cap_abs;
  c.max_shear = max_i1 > 0.0 ? shear / max_i1 : shear;
  c.strain_drift = 3.0 * midpoint_strain_drift(r, 0);
  return c;
}

/// Plot series of one comparison, every `every`-th step, with a name prefix.
void add_hydro_series(VerifyCase& c, const HydroComparison& h, const std::string& prefix, int every) {
  std::vector<std::vector<double>> cols(8);
  for (size_t k = 0; k < h.t.size(); ++k) {
    if (k % static_cast<size_t>(every) != 0 && k + 1 != h.t.size()) continue;
    // records[0] porosity is the static initial value, not the model's (see compare_hydrostatic): not plotted.
    const double phi = k == 0 ? std::nan("") : h.phi[k];
    const double v[8] = {h.ev[k], h.i1[k], h.i1_an[k], h.sqrt_j2[k], phi, h.phi_an[k], h.evp[k], h.evp_an[k]};
    for (int j = 0; j < 8; ++j) cols[static_cast<size_t>(j)].push_back(v[j]);
  }
  const char* names[8] = {"ev", "i1", "i1_an", "sqrt_j2", "porosity", "porosity_an", "evp", "evp_an"};
  for (int j = 0; j < 8; ++j) c.series.push_back({prefix + names[j], cols[static_cast<size_t>(j)]});
}

}  // namespace ballista
