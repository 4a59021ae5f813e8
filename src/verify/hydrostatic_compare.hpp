#pragma once
// A driven hydrostatic history (CATALOGUE A4, A5) against the exact response of
// hydrostatic_crush.hpp, step by step, and the sandstone-like parameter set those tests use.
#include <string>
#include <utility>
#include <vector>

#include "driver/point_driver.hpp"
#include "materials/material.hpp"
#include "verify/hydrostatic_crush.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

/// Drained porous sandstone in SI, chosen to resemble a Berea-type sandstone: K = 10 GPa,
/// G = 7 GPa, tensile vertex PEAKI1 = 10 MPa (3.3 MPa hydrostatic tension), FSLOPE = 0.3,
/// CR = 0.5; crush curve P0 = -90 MPa (pore collapse starts at 30 MPa mean pressure), P1 =
/// 1/(300 MPa), P3 = -ln(0.8) (initial porosity 20 %); then full crush is approached at I1 of a
/// few GPa (1 % of phi0 left at I1 = -1.50 GPa, 500 MPa mean pressure).
struct GeoSandstone {
  double density = 2300.0;
  double bulk = 10e9, shear = 7e9;
  double peak_i1 = 10e6, fslope = 0.3, cap_ratio = 0.5;
  double p0 = -90e6, p1 = 1.0 / 300e6;
  double phi0 = 0.2;
  double p3() const;  ///< -ln(1 - phi0)
  CrushCurve curve() const { return {p0, p1, p3()}; }
  HydroCapParams hydro(bool fixed_cap) const { return {bulk, peak_i1, curve(), fixed_cap}; }
  GeoReduction reduction(bool fixed_cap, double fluid_bulk = 0.0) const;
  /// Total volumetric strain at which the drained exact response reaches plastic volumetric
  /// strain evp on the compaction (or dilatation) branch: evp + X(evp)/(3K).
  double ev_on_cap(double evp) const { return evp + curve().cap(evp) / (3.0 * bulk); }
  /// Its parameters as plot/record scalars (p0, p1, p3, peak_i1, bulk, phi0).
  std::vector<std::pair<std::string, double>> scalars() const;
  /// Adds the analytic crush curve (thesis eq. 4.5) as series curve_i1 / curve_porosity, n + 1
  /// points from I1 = i1_from to i1_to, for the porosity-vs-I1 plots.
  void add_crush_curve(VerifyCase& c, double i1_from, double i1_to, int n) const;
};

/// Step-by-step comparison of a hydrostatic drive with the exact response.
struct HydroComparison {
  std::string missing;  ///< names of required state fields the model lacks (empty: all there)
  std::vector<double> t, ev, i1, i1_an, evp, evp_an, phi, phi_an, sqrt_j2;
  std::vector<int> leg;  ///< table row each step ends in (1-based)
  std::vector<int> compaction;  ///< 1 where the exact response is compacting
  std::vector<double> leg_i1_error;   ///< per leg: max |I1 - exact| / max |exact I1| on that leg
  std::vector<double> leg_i1_scale;   ///< per leg: max |exact I1|
  double max_i1_error = 0.0;          ///< max over legs of leg_i1_error
  double max_evp_error = 0.0;         ///< max |evp - exact| (only if the field exists)
  double max_phi_error = 0.0;         ///< max |porosity - exact (eq. 4.6 of the exact evp)|
  double phi_identity = 0.0;          ///< max |porosity - (1 - exp(-(P3 + evp)))| (model's own evp)
  double cap_consistency = 0.0;       ///< compaction steps: max |I1 - X(evp_model)| / max |I1|
  double max_shear = 0.0;             ///< max sqrt(J2) / max |I1|
  double strain_drift = 0.0;          ///< midpoint-vs-ln drift of ev over the run
};

/// Compares `r` (driven with hydrostatic rows at times row_t) with HydrostaticCap(p). Reads the
/// state fields plastic_volumetric_strain and porosity (geomodel contract).
HydroComparison compare_hydrostatic(const DriveResult& r, const HydroCapParams& p, const std::vector<double>& row_t);

/// Adds the comparison's series (ev, i1, i1_an, sqrt_j2, porosity, porosity_an, evp, evp_an), every
/// `every`-th step and the last, to c.series with the names prefixed by `prefix`.
void add_hydro_series(VerifyCase& c, const HydroComparison& h, const std::string& prefix, int every);

}  // namespace ballista
