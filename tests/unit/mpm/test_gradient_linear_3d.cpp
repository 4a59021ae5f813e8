// The velocity gradient of eight points per vector (mpm/gradient_linear_3d.hpp):
// against the general loop's sum over linear_stencil's nodes (to round-off: the compiler may fuse
// the general loop's multiply-adds differently), exact for a linear velocity field (linear
// weights reproduce it: L = A to round-off), and independent of which points share a group.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "mpm/gradient_linear_3d.hpp"

namespace ballista {
namespace {

GridGeometry box() {
  GridGeometry g;
  g.origin = Vec3{{-0.02, 0.01, 0.003}};
  g.h = 0.0025;
  g.nodes[0] = 6;
  g.nodes[1] = 5;
  g.nodes[2] = 4;
  g.dim = 3;
  return g;
}

/// n points in cell (2, 1, 1) at random offsets (a group of eight of them reads its nodes once).
std::vector<Vec3> points_in_a_cell(const GridGeometry& g, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x;
  for (int p = 0; p < n; ++p)
    x.push_back(Vec3{{g.origin[0] + (2 + u(rng)) * g.h, g.origin[1] + (1 + u(rng)) * g.h, g.origin[2] + (1 + u(rng)) * g.h}});
  return x;
}

std::vector<Mat3> gradients(const GridGeometry& g, const std::vector<Vec3>& vg, const std::vector<Vec3>& x, int group) {
  std::vector<Mat3> l(x.size());
  for (size_t p0 = 0; p0 < x.size(); p0 += group) {
    const int m = static_cast<int>(std::min<size_t>(group, x.size() - p0));
    linear_3d_gradients(g, vg.data(), &x[p0], m, &l[p0]);
  }
  return l;
}

/// Points in cell (2, 1, 1), in runs of several, and single points in other cells between them.
std::vector<Vec3> mixed_points(const GridGeometry& g, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x = points_in_a_cell(g, n, seed);
  for (size_t p = 0; p < x.size(); p += 3)
    x[p] = Vec3{{g.origin[0] + (3 * u(rng) + u(rng)) * g.h, g.origin[1] + (2 * u(rng) + u(rng)) * g.h,
                 g.origin[2] + (2 * u(rng) + u(rng)) * g.h}};
  return x;
}

TEST(GradientLinear3d, ReproducesALinearVelocityField) {
  const GridGeometry g = box();
  const Mat3 A{{1.5, -2.0, 0.25, 3.0, 0.5, -1.0, 0.75, 2.5, -0.5}};
  const Vec3 b{{10.0, -4.0, 2.0}};
  std::vector<Vec3> vg(g.node_count());
  for (int k = 0; k < g.nodes[2]; ++k)
    for (int j = 0; j < g.nodes[1]; ++j)
      for (int i = 0; i < g.nodes[0]; ++i) vg[g.node_index(i, j, k)] = A * g.node_position(i, j, k) + b;
  const std::vector<Vec3> x = mixed_points(g, 13, 3);
  const std::vector<Mat3> l = gradients(g, vg, x, kGradientGroup);
  // Linear weights reproduce a linear field: L = A up to the round-off of sums of size |v|/h.
  const double tol = 64 * 2.2e-16 * 12.0 / g.h;
  for (const Mat3& lp : l)
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(lp.a[k], A.a[k], tol);
}

TEST(GradientLinear3d, MatchesTheGeneralLoopAndDoesNotDependOnTheGroup) {
  const GridGeometry g = box();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> vg(g.node_count());
  for (Vec3& v : vg) v = Vec3{{100 * u(rng), 100 * u(rng), 100 * u(rng)}};
  const std::vector<Vec3> x = mixed_points(g, 21, 5);
  const std::vector<Mat3> by8 = gradients(g, vg, x, 8), by3 = gradients(g, vg, x, 3), by1 = gradients(g, vg, x, 1);
  double scale = 0.0;
  for (size_t p = 0; p < x.size(); ++p) {
    Stencil<3> st;
    linear_stencil<3>(g, x[p], st);
    Mat3 ref;
    for (int k = 0; k < st.count; ++k)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) ref(i, j) += vg[st.node[k]][i] * st.grad[k][j];
    for (int k = 0; k < 9; ++k) scale = std::max(scale, std::abs(ref.a[k]));
    for (int k = 0; k < 9; ++k) {
      // Bitwise across groupings: a point's lane never meets another point's.
      EXPECT_EQ(by8[p].a[k], by3[p].a[k]);
      EXPECT_EQ(by8[p].a[k], by1[p].a[k]);
      // Eight multiply-adds of terms up to 100 / h: a few ulps of that.
      EXPECT_NEAR(by8[p].a[k], ref.a[k], 16 * 2.2e-16 * 8 * 100 / g.h);
    }
  }
  EXPECT_GT(scale, 1e3);  // the field is not trivial
}

}  // namespace
}  // namespace ballista
