// The node-averaged F-bar of OTM (src/otm/otm_fbar.hpp) on synthetic supports, against what it
// must do by construction:
//  - a homogeneous step (every point the same L) is left as it is: every average of one value is
//    that value;
//  - the body's volume change is the standard update's, sum_p V^n dJbar_p = sum_p V^n dJ_p (the
//    shape functions are a partition of unity);
//  - each point keeps the isochoric part of its increment, dF / det(dF)^(1/m);
//  - in plane strain the out-of-plane row stays (F_zz, L_zz untouched);
//  - F_{n+1} = dFbar F_n, V = V_0 det F_{n+1} and Lbar = (dFbar - I)/dt agree;
//  - the result does not depend on the thread count (bitwise).
// Round-off: products and sums of ~10 terms of O(1): 1e-13 relative bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/parallel.hpp"
#include "otm/otm_fbar.hpp"

namespace ballista::otm::test_otm_fbar {
namespace {

constexpr double kDt = 1e-6;

struct Case {
  Supports sup;
  std::vector<Mat3> L, F, F0;
  std::vector<double> vol, vol0;
  Index nodes = 7;
};

/// n points, each on 3-5 of 7 nodes with positive weights summing to 1; F_n near I; L random
/// (|dt L| ~ 1e-2), or the same for every point.
Case make_case(bool homogeneous, bool plane, Index n = 40) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Case c;
  c.sup.offset.push_back(0);
  Mat3 common;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) common(i, j) = (u(rng) - 0.5) * 2e4;
  for (Index p = 0; p < n; ++p) {
    const int k = 3 + static_cast<int>(u(rng) * 3.0);
    std::vector<double> w(static_cast<std::size_t>(k));
    double sum = 0.0;
    for (double& x : w) sum += (x = 0.1 + u(rng));
    const int start = static_cast<int>(u(rng) * static_cast<double>(c.nodes - k + 1));
    for (int i = 0; i < k; ++i) {
      c.sup.node.push_back(start + i);
      c.sup.N.push_back(w[static_cast<std::size_t>(i)] / sum);
      c.sup.dN.push_back(Vec3{});
    }
    c.sup.offset.push_back(static_cast<Index>(c.sup.node.size()));
    Mat3 l = common, Fn = Mat3::identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        if (!homogeneous) l(i, j) = (u(rng) - 0.5) * 2e4;
        Fn(i, j) += (u(rng) - 0.5) * 0.1;
      }
    if (plane) {
      for (int i = 0; i < 3; ++i) l(2, i) = l(i, 2) = Fn(2, i) = Fn(i, 2) = 0.0;
      Fn(2, 2) = 1.0;
    }
    const double v0 = 1e-6 * (0.5 + u(rng));
    const Mat3 F1 = (Mat3::identity() + kDt * l) * Fn;
    c.L.push_back(l);
    c.F0.push_back(Fn);
    c.F.push_back(F1);
    c.vol0.push_back(v0);
    c.vol.push_back(v0 * det(F1));
  }
  return c;
}

FBarFields fields(Case& c) {
  return {static_cast<Index>(c.L.size()), c.L.data(), c.F.data(), c.vol.data(), c.vol0.data(), nullptr, nullptr};
}

double ratio(const Mat3& dF, bool plane) {
  return plane ? dF(0, 0) * dF(1, 1) - dF(0, 1) * dF(1, 0) : det(dF);
}

TEST(OtmFBar, AHomogeneousStepIsLeftAsItIs) {
  for (bool plane : {false, true}) {
    Case c = make_case(true, plane);
    const Case before = c;
    NodalFBar().apply(c.sup, c.nodes, plane, kDt, fields(c));
    for (std::size_t p = 0; p < c.L.size(); ++p)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          EXPECT_NEAR(c.F[p](i, j), before.F[p](i, j), 1e-13) << p;
          EXPECT_NEAR(c.L[p](i, j), before.L[p](i, j), 1e-13 * 1e4) << p;  // |L| ~ 1e4 1/s
        }
  }
}

TEST(OtmFBar, KeepsTheVolumeChangeAndEachPointsIsochoricPart) {
  for (bool plane : {false, true}) {
    Case c = make_case(false, plane);
    const Case before = c;
    NodalFBar().apply(c.sup, c.nodes, plane, kDt, fields(c));
    const double m = plane ? 2.0 : 3.0;
    double vn_dj = 0.0, vn_djbar = 0.0, vn_sum = 0.0;
    bool changed = false;
    for (std::size_t p = 0; p < c.L.size(); ++p) {
      const Mat3 dF = Mat3::identity() + kDt * before.L[p];
      const Mat3 dFbar = Mat3::identity() + kDt * c.L[p];
      const double vn = before.vol[p] / ratio(dF, plane);
      vn_sum += vn;
      vn_dj += vn * ratio(dF, plane);
      vn_djbar += vn * ratio(dFbar, plane);
      changed = changed || std::abs(ratio(dFbar, plane) / ratio(dF, plane) - 1.0) > 1e-6;
      const double a = std::pow(ratio(dF, plane), -1.0 / m), b = std::pow(ratio(dFbar, plane), -1.0 / m);
      const Mat3 Fnext = dFbar * before.F0[p];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const bool in_plane = !plane || (i < 2 && j < 2);
          if (in_plane) EXPECT_NEAR(b * dFbar(i, j), a * dF(i, j), 1e-13) << p;  // isochoric part
          else EXPECT_EQ(c.L[p](i, j), before.L[p](i, j)) << p;                   // F_zz row, L_zz
          EXPECT_NEAR(c.F[p](i, j), Fnext(i, j), 1e-13) << p;
        }
      EXPECT_NEAR(c.vol[p], c.vol0[p] * det(c.F[p]), 1e-13 * c.vol[p]) << p;
    }
    EXPECT_TRUE(changed);  // the points' volume changes differed, so the averages moved them
    EXPECT_NEAR(vn_djbar, vn_dj, 1e-14 * vn_sum);
  }
}

TEST(OtmFBar, ThreadCountIndependent) {
  // Above kParallelThreshold points, so that two threads share the per-point passes.
  Case a = make_case(false, false, 6000), b = a;
  const int threads = max_threads();
  set_threads(1);
  NodalFBar().apply(a.sup, a.nodes, false, kDt, fields(a));
  set_threads(2);
  NodalFBar().apply(b.sup, b.nodes, false, kDt, fields(b));
  set_threads(threads);
  for (std::size_t p = 0; p < a.L.size(); ++p) {
    EXPECT_EQ(a.vol[p], b.vol[p]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_EQ(a.F[p](i, j), b.F[p](i, j));
  }
}

}  // namespace
}  // namespace ballista::otm::test_otm_fbar
