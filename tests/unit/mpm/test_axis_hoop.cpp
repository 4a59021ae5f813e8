// The hoop operator of axisymmetric uGIMP next to the axis (mpm/axis_hoop.hpp), against what it
// must be in exact arithmetic: the uniform expansion v_r = a r has the hoop rate a wherever the
// particle is (sum_I r_I N_I = r on r >= 0); a domain inside r >= 0 gives N_I / r_p; the operator
// stays bounded as the particle reaches the axis (the plain N_I / r_p does not: the first node's
// weight tends to l / 4h). Bounds: sums of at most 9 rounded terms of size <= 1/l, 1e-12
// relative; the bound 2 / l is the operator's own (denominator l^2 / 2, numerator <= l).
#include <gtest/gtest.h>

#include <cmath>

#include "mpm/axis_hoop.hpp"
#include "mpm/graded_shape_functions.hpp"

namespace test_axis_hoop {

using namespace ballista;

namespace {

/// An axisymmetric grid block as the solver lays it out: two ghost node layers below the axis,
/// the axis at block index 2, cells of h (or a graded axis with cells growing away from it).
GridGeometry axis_grid(bool graded) {
  GridGeometry g;
  g.dim = 2;
  g.h = 1e-3;
  g.origin = Vec3{{-2e-3, -2e-3, 0.0}};
  g.nodes[0] = 20;
  g.nodes[1] = 20;
  g.nodes[2] = 1;
  if (graded) {
    auto axes = std::make_shared<std::array<GradedAxis, 3>>();
    std::vector<double> r{-2e-3, -1e-3, 0.0}, z;
    double h = 1e-3;
    for (int k = 3; k < 20; ++k) {
      if (k > 6) h *= 1.2;
      r.push_back(r.back() + h);
    }
    for (int k = 0; k < 20; ++k) z.push_back(-2e-3 + k * 1e-3);
    (*axes)[0] = GradedAxis(r);
    (*axes)[1] = GradedAxis(z);
    (*axes)[2] = GradedAxis({0.0, 1.0});
    g.graded = axes;
  }
  return g;
}

Stencil<2> gimp_weights(const GridGeometry& g, const Vec3& x, const Vec3& lp) {
  Stencil<2> s;
  if (g.graded) graded_gimp_stencil<2>(g, x, lp, s);
  else gimp_stencil<2>(g, x, lp, s);
  return s;
}

}  // namespace

TEST(AxisHoop, UniformExpansionGivesItsRateOnEitherSideOfTheAxisEdge) {
  // v_r = a r at the nodes (the ghost nodes carry 0, as the solver's axis condition sets them).
  const double a = 3.7e4, lp = 0.25e-3;
  for (bool graded : {false, true}) {
    const GridGeometry g = axis_grid(graded);
    for (double r : {1e-9, 1e-6, 0.05e-3, 0.1e-3, 0.2e-3, 0.2499e-3}) {
      const Vec3 x{{r, 4.3e-3, 0.0}};
      const Stencil<2> s = gimp_weights(g, x, Vec3{{lp, lp, 0.0}});
      double hoop[Stencil<2>::kMax];
      ASSERT_TRUE(axis_hoop_weights(g, r, lp, s, hoop)) << "r = " << r;
      double rate = 0.0;
      for (int k = 0; k < s.count; ++k) {
        const Vec3 node = g.node_position(static_cast<int>(s.node[k] % g.nodes[0]),
                                          static_cast<int>(s.node[k] / g.nodes[0]), 0);
        rate += hoop[k] * (node[0] > 0.0 ? a * node[0] : 0.0);
      }
      EXPECT_NEAR(rate, a, 1e-12 * a) << "graded " << graded << ", r = " << r;
    }
  }
}

TEST(AxisHoop, DomainClearOfTheAxisKeepsTheUsualOperator) {
  const GridGeometry g = axis_grid(false);
  const double lp = 0.25e-3;
  double hoop[Stencil<2>::kMax];
  for (double r : {0.25e-3, 0.3e-3, 2.6e-3}) {
    const Stencil<2> s = gimp_weights(g, Vec3{{r, 4.3e-3, 0.0}}, Vec3{{lp, lp, 0.0}});
    EXPECT_FALSE(axis_hoop_weights(g, r, lp, s, hoop)) << "r = " << r;
  }
  // Just inside the edge the domain average meets w / r: continuous at r = l.
  const double r = lp * (1.0 - 1e-9);
  const Stencil<2> s = gimp_weights(g, Vec3{{r, 4.3e-3, 0.0}}, Vec3{{lp, lp, 0.0}});
  ASSERT_TRUE(axis_hoop_weights(g, r, lp, s, hoop));
  for (int k = 0; k < s.count; ++k) EXPECT_NEAR(hoop[k], s.w[k] / r, 1e-6 / lp) << "entry " << k;
}

TEST(AxisHoop, BoundedAsTheParticleReachesTheAxis) {
  const GridGeometry g = axis_grid(false);
  const double lp = 0.25e-3;
  for (double r : {1e-7, 1e-10, 1e-13}) {
    const Stencil<2> s = gimp_weights(g, Vec3{{r, 4.3e-3, 0.0}}, Vec3{{lp, lp, 0.0}});
    double hoop[Stencil<2>::kMax];
    ASSERT_TRUE(axis_hoop_weights(g, r, lp, s, hoop));
    double plain = 0.0, largest = 0.0;
    for (int k = 0; k < s.count; ++k) {
      largest = std::max(largest, std::fabs(hoop[k]));
      plain = std::max(plain, s.w[k] / r);
    }
    EXPECT_LE(largest, 2.0 / lp) << "r = " << r;
    // The form it replaces: the first node off the axis keeps weight ~ l / 4h, so w / r ~ 1 / (16 r).
    EXPECT_GT(plain, 0.01 / r) << "r = " << r;
  }
}

}  // namespace test_axis_hoop
