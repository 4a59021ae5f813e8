// CATALOGUE A3 through the single-element driver (problem: a3_drucker_prager_vertex.hpp).
//
// Error measure. At each published time the error is |sigma - sigma_pub|_F / |sigma_pub|_F
// (Frobenius norm of the whole tensor, off-diagonals included): invariant, and never divided by
// a small component (sigma11 = 20.6 Pa at t = 3 next to sigma22 = -175 Pa). The headline is the
// largest over t = 1, 1.5, 2, 2.5, 3; the catalogue asks for 1 %.
// What a correct model can differ by: the published numbers hold for ln F (I1(1) = 9 K ln 0.9906
// = -850.00002); the model integrates the midpoint increments (Hughes & Winget 1980), which drift
// from ln F by sum (l - 1)^3/12, O(1e-12) here; the table's F are rounded to 9 digits, 7e-8 in
// the stresses (the exact integrator of drucker_prager_triaxial.hpp on the same table); the
// solution is linear on the flat cone, so an exact return has no step-size error at all. So the
// observed error of a correct model is ~1e-7 and its convergence "order" with the step count ~0;
// a model whose return is only first-order accurate (e.g. an explicit flow update) shows its
// order in the scalars convergence_order (errors at N/4, N/2, N steps per row).
#include "verify/a3_drucker_prager_vertex.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "driver/point_driver.hpp"
#include "verify/drucker_prager_triaxial.hpp"
#include "verify/geo_hooks.hpp"
#include "verify/hook_material.hpp"

namespace ballista {

namespace {

Mat3 published(size_t row) {
  const double s22 = A3Reference::sigma22()[row];
  return Mat3::diag(A3Reference::sigma11()[row], s22, s22);
}

DriveResult drive(const Material& m, int substeps) {
  const auto &t = A3Reference::t(), &F11 = A3Reference::F11(), &F22 = A3Reference::F22();
  return drive_diagonal(m, {t.begin(), t.end()}, {F11.begin(), F11.end()}, {F22.begin(), F22.end()}, substeps);
}

/// Relative error at each published time t = 1 ... 3 (rows 1 ... 5).
std::vector<double> row_errors(const DriveResult& r) {
  std::vector<double> e;
  for (size_t row = 1; row < A3Reference::t().size(); ++row) {
    const Mat3 pub = published(row);
    e.push_back(frobenius(r.records[record_nearest(r, A3Reference::t()[row])].sigma - pub) / frobenius(pub));
  }
  return e;
}

}  // namespace

VerifyCase run_a3(const MaterialFactory& f, const A3Problem& pb) {
  const std::string id = "A3";
  const std::string title =
      "A3 linear Drucker-Prager vertex test (Brannon & Leelavanichkul 2010): K = 1e4, G = 3750, PEAKI1 = 150, "
      "FSLOPE = 0.2357, beta = 1/2";
  if (!f.reduce_geo)
    return VerifyCase::not_applicable(f.model, id, title,
                                      kNoGeoHookReason);
  GeoReduction g;
  g.density = pb.density;
  g.bulk = A3Reference::kBulk;
  g.shear = A3Reference::kShear;
  g.peak_i1 = A3Reference::peak_i1();
  g.fslope = A3Reference::fslope();
  g.cap_ratio = 0.5;  // irrelevant: no cap (p3 = 0)
  g.flow_beta = A3Reference::kBeta;  // the published answer needs beta = 1/2 (drucker_prager_triaxial.hpp)
  const ParamValues v = f.reduce_geo(g);
  if (v.empty() && v.choices.empty())
    return VerifyCase::not_applicable(f.model, id, title,
                                      "reduce_geo returns no parameters for non-associative flow (beta = 1/2)");
  const auto mat = make_hook_material(f, v, "reduce_geo");

  VerifyCase c = VerifyCase::begin(f.model, id, title, "a3");

  // Three step counts: headline N, and N/4, N/2 for the observed convergence.
  const int N = pb.substeps;
  const std::vector<int> counts{N / 4, N / 2, N};
  std::vector<double> max_err;
  DriveResult res;
  std::vector<double> errs;
  for (int n : counts) {
    res = drive(*mat, n);
    errs = row_errors(res);
    max_err.push_back(*std::max_element(errs.begin(), errs.end()));
  }
  const double order = std::log2(max_err[1] / max_err[2]);
  const double tol = 1e-2;
  c.max_rel_error = max_err[2];
  c.tolerance = tol;
  c.error_measure =
      "max over t = 1, 1.5, 2, 2.5, 3 of |sigma - sigma_published|_F / |sigma_published|_F (whole tensor)";
  c.tolerance_justification =
      "catalogue A3: the published stresses within 1 %. A correct model is at ~1e-7 (9-digit F table; exact "
      "return on the flat cone); a wrong flow rule (beta = 1) is 33 % off at t = 2";
  c.check("published stresses, worst of t = 1 ... 3 (relative, Frobenius)", max_err[2], tol);
  for (size_t k = 0; k < errs.size(); ++k)
    c.check(fmt::format("published stress at t = {:g}", A3Reference::t()[k + 1]), errs[k], tol);

  // Admissibility at every step, and the exact solution along the whole path for the plot (and a
  // check: the same measure against the exact integrator fed the model's own ln F increments).
  const DruckerPragerParams dp = A3Reference::params();
  DruckerPragerTriaxial exact(dp);
  double overshoot = -std::numeric_limits<double>::infinity(), err_path = 0.0, scale_path = 0.0;
  std::vector<double> t, s11, s22, s33, i1, rj2, a11, a22, ai1, arj2;
  const size_t n = res.records.size();
  std::vector<Mat3> exact_sigma(n);
  for (size_t k = 0; k < n; ++k) {
    const DriveRecord& r = res.records[k];
    if (k > 0) {
      const Mat3& Fo = res.records[k - 1].F;
      exact.advance(std::log(r.F(0, 0) / Fo(0, 0)), std::log(r.F(1, 1) / Fo(1, 1)));
    }
    const Mat3& s = r.sigma;
    const Mat3 d = deviator(s);
    const double sqrt_j2 = std::sqrt(0.5 * ddot(d, d));
    const double limit = dp.limit(trace(s));
    overshoot = std::max(overshoot, limit > 0.0 ? sqrt_j2 / limit - 1.0 : std::numeric_limits<double>::infinity());
    const Mat3 an = Mat3::diag(exact.sigma11(), exact.sigma22(), exact.sigma22());
    exact_sigma[k] = an;
    err_path = std::max(err_path, frobenius(s - an));
    scale_path = std::max(scale_path, frobenius(an));
    if (k % static_cast<size_t>(pb.plot_every) == 0 || k + 1 == n) {
      t.push_back(r.t);
      s11.push_back(s(0, 0));
      s22.push_back(s(1, 1));
      s33.push_back(s(2, 2));
      i1.push_back(trace(s));
      rj2.push_back(sqrt_j2);
      a11.push_back(exact.sigma11());
      a22.push_back(exact.sigma22());
      ai1.push_back(exact.i1());
      arj2.push_back(exact.sqrt_j2());
    }
  }
  err_path /= scale_path;

  // Dwell: the stress stays at its t = 1.5 value up to t = 2 (same measure and tolerance). Exactly
  // so only at the row ends: inside the row the linearly interpolated F makes a ln-strain path that
  // bows off the flow direction M, and the exact solution itself leaves the dwell point by a few
  // 1e-3 before returning at t = 2 (path independence on the flat cone); reported as a scalar.
  const size_t k15 = record_nearest(res, 1.5), k2 = record_nearest(res, 2.0);
  double dwell = 0.0, wander = 0.0;
  for (size_t k = k15; k <= k2; ++k) {
    dwell = std::max(dwell, frobenius(res.records[k].sigma - res.records[k15].sigma) / frobenius(published(2)));
    wander = std::max(wander, frobenius(exact_sigma[k] - exact_sigma[k15]) / frobenius(published(2)));
  }
  c.check("dwell: |sigma(t) - sigma(1.5)| / |sigma_published(1.5)| for t in [1.5, 2]", dwell, tol);
  // A return that ends on the surface leaves f at its solver tolerance (1e-10 relative or round-off);
  // 1e-6 admits iterative returns and catches a wrong surface, which the 1 % stress tolerance might not.
  c.check("sqrt(J2) <= Ff(I1) (1 + 1e-6) at every step: max sqrt(J2)/Ff - 1", overshoot, 1e-6);
  c.check("all steps vs the exact integrator (ln F path), |sigma - exact|_F / max |exact|_F", err_path, tol);

  std::vector<double> tab_t, tab_11, tab_22;
  for (size_t k = 0; k < A3Reference::t().size(); ++k) {
    tab_t.push_back(A3Reference::t()[k]);
    tab_11.push_back(A3Reference::sigma11()[k]);
    tab_22.push_back(A3Reference::sigma22()[k]);
  }
  c.series = {{"t", t},         {"s11", s11},         {"s22", s22},      {"s33", s33},     {"i1", i1},
              {"sqrt_j2", rj2}, {"s11_an", a11},      {"s22_an", a22},   {"i1_an", ai1},   {"sqrt_j2_an", arj2},
              {"table_t", tab_t}, {"table_s11", tab_11}, {"table_s22", tab_22}};
  c.scalars = {{"peak_i1", dp.peak_i1},
               {"fslope", dp.fslope},
               {"beta", dp.beta},
               {"steps_per_row", static_cast<double>(N)},
               {"max_error_quarter_steps", max_err[0]},
               {"max_error_half_steps", max_err[1]},
               {"max_error_steps", max_err[2]},
               {"convergence_order", order},
               {"dwell_error", dwell},
               {"dwell_exact_wander", wander},
               {"max_yield_overshoot", overshoot},
               {"strain_drift", midpoint_strain_drift(res, 0) + midpoint_strain_drift(res, 1)}};
  c.finish();
  return c;
}

}  // namespace ballista
