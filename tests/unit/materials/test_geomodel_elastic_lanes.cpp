// The geomodel's elastic steps kLanes points at a time (materials/geomodel_elastic_lanes.hpp)
// against Geomodel::update, point by point: every point the lanes take must be update()'s to the
// bit (stress, every state field, what the step reports), the points they leave must be left as
// they were, and they must leave every point update() finds plastic. The bounds of the limit
// surface that decide it (GeoLimit::bounds) must enclose the surface.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "materials/geomodel.hpp"

namespace ballista::test_geomodel_elastic_lanes {
namespace {

/// The drained Berea preset's parameters (data/materials.yaml, sandstone_berea_drained): the
/// nonlinear limit surface (stren given), the cap and crush curve, no fluid, no rate term.
ParamValues berea_drained() {
  return {{"density", 2094.0},  {"bulk_modulus", 6.6e9}, {"shear_modulus", 5.6e9}, {"peak_i1", 33.0e6},
          {"fslope", 0.40},     {"stren", 320.0e6},      {"yslope", 0.0},         {"cap_ratio", 3.4},
          {"crush_p0", -1.14e9}, {"crush_p1", 5.0e-10},  {"crush_p3", 0.2357}};
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(GeomodelSurface, BoundsEncloseTheLimitSurface) {
  std::mt19937 rng(7);
  for (const GeoLimit& f : {GeoLimit::make(33e6, 0.40, 320e6, 0.0), GeoLimit::make(20e6, 0.45, 150e6, 0.05),
                            GeoLimit::make(33e6, 0.40, NAN, 0.0)}) {
    std::uniform_real_distribution<double> u(-8e9, f.peak_i1);
    for (int i = 0; i < 20000; ++i) {
      const double i1 = i < 3 ? (i == 0 ? f.peak_i1 : i == 1 ? 0.0 : -1e12) : u(rng);
      double lo, hi;
      f.bounds(i1, lo, hi);
      const double v = f.value(i1);
      ASSERT_LE(lo, v) << i1;
      ASSERT_GE(hi, v) << i1;
      // Tight where the surface is used: the gap is ~4 (a2 I1/8)^2 of a3 exp(a2 I1) for |a2 I1| <= 0.2,
      // plus the 1e-12 rounding margin; 1 % of a3 is ample and still makes the check useful.
      if (std::abs(f.a2 * i1) <= 0.2) {
        EXPECT_LE(hi - lo, 0.01 * f.a3 + 1e-9 * (std::abs(f.a1) + std::abs(f.a4 * i1)));
      }
    }
  }
}

/// A rock scaled down 50 times in strength, with a narrow cap (cap_ratio 0.2): its surface is
/// small against a step's trial increment, so elastic steps need several substeps.
ParamValues small_surface() {
  ParamValues v = berea_drained();
  v["peak_i1"] = 2e6;
  v["stren"] = 20e6;
  v["cap_ratio"] = 0.2;
  v["crush_p0"] = -30e6;
  v["crush_p1"] = 1e-8;
  return v;
}

struct Case {
  ParamValues params;
  double mean_lo, mean_hi;  ///< range of the mean stress, Pa
  double shear;             ///< largest sqrt(J2), Pa
  double rate;              ///< strain rate scale, 1/s
  /// Half the lanes reverse their deviator in one step (D = -1.9 s / (2 G dt)): an elastic step
  /// whose trial increment, 1.9 times the deviator, may exceed the surface's size.
  bool reverse = false;
};

/// Runs `groups` groups of kLanes random points through both paths; returns the counts.
struct Counts {
  int total = 0, taken = 0, taken_multi = 0, plastic = 0;
};
Counts check_case(const Case& c, int groups, unsigned seed) {
  const Geomodel::Params p = Geomodel::make(c.params);
  EXPECT_TRUE(Geomodel::elastic_lanes_apply(p));
  const int ns = 5;  // eqps, evp, substeps, porosity, cap_i1
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double dt = 2e-8;
  Counts n;
  for (int g = 0; g < groups; ++g) {
    LaneKinematics k;
    k.dt = dt;
    Mat3L sigma;
    Lane st[ns];
    LaneMask want;
    for (int l = 0; l < kLanes; ++l) {
      // Mean stress over the case's range, a deviator up to its shear, strain rates up to its
      // rate (one lane in five 30 times more: several substeps, mostly plastic); evp 0, or crushed
      // or dilated (which the lanes leave to update()).
      const double mean = c.mean_lo + (c.mean_hi - c.mean_lo) * 0.5 * (1.0 + u(rng));
      Mat3 dev;
      for (double& x : dev.a) x = u(rng);
      dev = deviator(sym(dev));
      const double scale = c.shear * 0.5 * (1.0 + u(rng)) / std::sqrt(0.5 * ddot(dev, dev));
      const Mat3 s = scale * dev + mean * Mat3::identity();
      Mat3 D;
      for (double& x : D.a) x = (l % 5 == 4 ? 30.0 : 1.0) * c.rate * u(rng);
      D = sym(D);
      if (c.reverse && l % 2 == 0) D = (-1.9 / (2.0 * p.G0 * dt)) * (scale * dev);
      sigma.set_lane(l, s);
      k.D_bar.set_lane(l, D);
      const int kind = (g + l) % 4;
      const double evp = kind == 1 ? -0.01 * (1.0 + u(rng)) : kind == 2 ? 0.01 * (1.0 + u(rng)) : 0.0;
      st[0][l] = kind == 0 ? 0.0 : 0.02 * (1.0 + u(rng));
      st[1][l] = evp;
      st[2][l] = 1.0;
      st[3][l] = p.crush.porosity(evp);
      st[4][l] = p.crush.cap(evp);
      want[l] = (g + l) % 9 == 8 ? 0 : -1;  // some lanes not offered
    }
    Mat3L sigma_l = sigma;
    Lane st_l[ns];
    for (int s = 0; s < ns; ++s) st_l[s] = st[s];
    PointResult res_l[kLanes];
    Lane work_l = splat(-1.0);
    const LaneMask done = Geomodel::update_lanes_elastic(p, k, want, sigma_l, st_l, res_l, work_l);
    for (int l = 0; l < kLanes; ++l) {
      ++n.total;
      PointKinematics pk;
      pk.dt = dt;
      pk.D_bar = k.D_bar.lane(l);
      Mat3 s = sigma.lane(l);
      double sl[ns];
      for (int i = 0; i < ns; ++i) sl[i] = st[i][l];
      PointResult res;
      Geomodel::update(p, pk, s, sl, res);
      if (res.delta_eqps > 0.0) ++n.plastic;
      if (!done[l]) {
        // Left for update(): untouched.
        for (int e = 0; e < 9; ++e) EXPECT_TRUE(same_bits(sigma_l.a[e][l], sigma.a[e][l]));
        for (int i = 0; i < ns; ++i) EXPECT_TRUE(same_bits(st_l[i][l], st[i][l]));
        continue;
      }
      ++n.taken;
      if (sl[2] > 1.0) ++n.taken_multi;
      EXPECT_EQ(st[1][l], 0.0) << "crushed or dilated rock is left to update()";
      EXPECT_TRUE(want[l]) << "a lane not offered was taken";
      EXPECT_EQ(res.delta_eqps, 0.0) << "a plastic step was taken as elastic";
      for (int e = 0; e < 9; ++e) EXPECT_TRUE(same_bits(sigma_l.a[e][l], s.a[e])) << "group " << g << " lane " << l;
      for (int i = 0; i < ns; ++i) EXPECT_TRUE(same_bits(st_l[i][l], sl[i])) << "state " << i;
      // What the lanes report for a point taken: update()'s result of the elastic step.
      EXPECT_TRUE(same_bits(res.eqps, res_l[l].eqps));
      EXPECT_TRUE(same_bits(res.delta_eqps, res_l[l].delta_eqps));
      EXPECT_TRUE(same_bits(res.plastic_work_density, res_l[l].plastic_work_density));
      EXPECT_TRUE(same_bits(res.drucker_product, res_l[l].drucker_product));
      EXPECT_TRUE(same_bits(res.plastic_work_density, work_l[l]));
    }
  }
  return n;
}

TEST(GeomodelElasticLanes, ThePointsTakenAreUpdatesToTheBit) {
  // Berea: mean stress from 3 MPa of tension to 150 MPa of compression, sqrt(J2) up to 120 MPa
  // (Ff is 20 MPa at I1 = 0 and 132 MPa at I1 = -450 MPa), strain increments 0.2 % (some 6 %).
  const Counts a = check_case({berea_drained(), -150e6, 3e6, 120e6, 1e5}, 4000, 11);
  // The small surface (size 16 MPa, Ff 6.6 to 8.1 MPa over the mean stresses here, cap region
  // below I1 - X = 1.6 MPa), its deviators reversed in one step on half the lanes.
  const Counts b = check_case({small_surface(), -9e6, -6e6, 6.5e6, 1e4, true}, 4000, 12);
  // The mix the check needs: many points taken (of the half with evp = 0), some with several
  // substeps, and plastic points (all of them left to update(), checked above).
  EXPECT_GT(a.taken, a.total / 5);
  EXPECT_GT(a.plastic, a.total / 20);
  EXPECT_GT(b.taken_multi, b.total / 100);
  EXPECT_GT(b.plastic, b.total / 20);
  std::printf("Berea: %d of %d taken, %d plastic; small surface: %d taken (%d with substeps), %d plastic\n",
              a.taken, a.total, a.plastic, b.taken, b.taken_multi, b.plastic);
}

}  // namespace
}  // namespace ballista::test_geomodel_elastic_lanes
