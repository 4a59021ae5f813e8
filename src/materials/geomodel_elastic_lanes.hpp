#pragma once
// The geomodel's elastic steps kLanes points at a time (material_lanes.hpp), bitwise those of
// Geomodel::update for every point they take. Most of a target's rock is inside its yield surface
// at most steps; for it, update() computes the substep count, the elastic trials and the yield
// check one point at a time. Here the trials run on kLanes points per instruction and the yield
// check is Geomodel::certainly_elastic, which needs no exponential and is never true where
// update() would find the point plastic. A point that is not certainly elastic at every substep
// is left untouched for update().
//
// Bitwise, not only to round-off (unlike core/lanes.hpp's general promise): every tensor
// operation below is the one update() and substep() evaluate, in the same order, and the
// decisions (substep count, yield check) are made per point with the scalar functions.
// test_geomodel_elastic_lanes.cpp checks that every point taken is update()'s to the bit, and
// the examples' results are compared bitwise with the build before (tools/compare_builds.py).
//
// It applies where update()'s elastic step has no terms beyond these: constant moduli (B1 = 0,
// no pressure-dependent Poisson ratio), no pore fluid and no rate dependence (T1 = 0); the drained
// Berea presets are such sets.
#include "materials/geomodel.hpp"

namespace ballista {

inline bool Geomodel::elastic_lanes_apply(const Params& p) {
  return p.T1 == 0.0 && !p.fluid() && p.B1 == 0.0 && !p.poisson;
}

inline LaneMask Geomodel::update_lanes_elastic(const Params& p, const LaneKinematics& k, LaneMask want, Mat3L& sigma,
                                               Lane* st, PointResult* res, Lane& plastic_work) {
  // As update(): eps = D_bar dt, the moduli of the step (moduli() with B1 = 0: K = B0 + B1 0, G = G0).
  const Mat3L eps = k.dt * k.D_bar;
  const double K = p.B0 + p.B1 * 0.0, G = p.G0;
  const Lane tr_e = trace(eps);
  const Mat3L dev = deviator(eps);
  const Lane dsig = lane_sqrt(9.0 * K * K * tr_e * tr_e / 3.0 + 4.0 * G * G * ddot(dev, dev));
  // Per point, as update(): the cap and the substep count.
  // A point whose rock has crushed or dilated (evp != 0) is left to update(): its cap costs a log
  // or a pow, and such points, at the edge of a crater, are mostly yielding. So every point taken
  // has the uncrushed cap X = cap_at(p, 0).
  const double X = cap_at(p, 0.0);
  const Lane I1_n = trace(sigma);
  int n[kLanes];
  int n_max = 0;
  Lane inv_n;
  LaneMask live = want;
  for (int l = 0; l < kLanes; ++l) {
    if (!want[l] || st[1][l] != 0.0) {
      live[l] = 0;
      n[l] = 0;
      inv_n[l] = 0.0;
      continue;
    }
    const double i1e = I1_n[l] + 3.0 * 0.0;  // pf_n = 0: drained
    const double n_need = std::ceil(dsig[l] / surface_size(p, X, i1e));
    n[l] = std::isfinite(n_need) ? static_cast<int>(std::clamp(n_need, 1.0, double(p.max_substeps))) : p.max_substeps;
    inv_n[l] = 1.0 / n[l];
    n_max = std::max(n_max, n[l]);
  }
  const Mat3L deps = inv_n * eps;
  const Lane tr_d = trace(deps);
  // substep()'s elastic trial, as many times as each point's count; a point found not certainly
  // elastic drops out (update() will redo its whole step).
  const double iso_factor = K - 2.0 * G / 3.0;
  Mat3L s = sigma;
  for (int i = 0; i < n_max && any(live); ++i) {
    Mat3L sig_t = s + (2.0 * G) * deps;
    const Lane iso = iso_factor * tr_d;
    sig_t.a[0] += iso;
    sig_t.a[4] += iso;
    sig_t.a[8] += iso;
    const Lane I1_t = trace(sig_t);
    const Mat3L s_t = deviator(sig_t);
    const Lane rj2_t = lane_sqrt(0.5 * ddot(s_t, s_t));
    LaneMask step = live;
    for (int l = 0; l < kLanes; ++l) {
      if (!live[l] || i >= n[l]) {
        step[l] = 0;
        continue;
      }
      // substep(): a deviator at the round-off level of the stress counts as zero.
      const double rj2 = rj2_t[l] <= 1e-13 * std::abs(I1_t[l]) ? 0.0 : rj2_t[l];
      if (!certainly_elastic(p, X, I1_t[l] + 3.0 * 0.0, rj2)) {
        live[l] = 0;
        step[l] = 0;
      }
    }
    for (int e = 0; e < 9; ++e) s.a[e] = select(step, sig_t.a[e], s.a[e]);
  }
  for (int e = 0; e < 9; ++e) sigma.a[e] = select(live, s.a[e], sigma.a[e]);
  Lane n_lane;
  for (int l = 0; l < kLanes; ++l) n_lane[l] = n[l];
  st[2] = select(live, n_lane, st[2]);           // update() stores the count,
  st[0] = select(live, st[0] + 0.0, st[0]);       // and eqps + 0 (its increment), evp as it was
  for (int l = 0; l < kLanes; ++l) {
    if (!live[l]) continue;
    // What update() reports for an elastic step (its drucker_product, ddot(sigma - sigma_n, 0), is +0).
    res[l].eqps = st[0][l];
    res[l].delta_eqps = 0.0;
    res[l].plastic_work_density = 0.0;
    res[l].drucker_product = 0.0;
    plastic_work[l] = 0.0;
  }
  return live;
}

}  // namespace ballista
