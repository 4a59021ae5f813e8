// Shape functions on a graded grid (mpm/graded_shape_functions.hpp): partition of unity, linear
// completeness (sum N_I x_I = x, sum grad N_I x_I^T = I), the uGIMP gradient as the derivative of
// its weight, and on equal cells the uniform grid's weights to round-off. Bounds: identities exact
// in real arithmetic against 1e-12 (a few hundred rounded terms of size <= the grid's extent);
// the finite difference's truncation error O(delta^2 |S'''|) is below 1e-6 at delta = 1e-7 h.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mpm/graded_shape_functions.hpp"

namespace test_graded_shape_functions {

using namespace ballista;

namespace {

/// A grid of 24 nodes per axis whose cells vary randomly by up to 1.5x between neighbours, or
/// equal cells of 0.25 (`uniform`), from the same origin as a uniform GridGeometry.
GridGeometry graded_grid(int dim, bool uniform, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ratio(1.0 / 1.5, 1.5);
  GridGeometry g;
  g.origin = Vec3{{-0.3, 0.7, 1.1}};
  g.dim = dim;
  g.h = 0.25;
  auto axes = std::make_shared<std::array<GradedAxis, 3>>();
  for (int a = 0; a < 3; ++a) {
    std::vector<double> x{g.origin[a]};
    double h = 0.25;
    for (int k = 1; k < 24; ++k) {
      if (!uniform) h = std::clamp(h * ratio(rng), 0.1, 0.6);
      x.push_back(uniform ? g.origin[a] + k * 0.25 : x.back() + h);
    }
    (*axes)[a] = GradedAxis(x);
    g.nodes[a] = a < dim ? 24 : 1;
  }
  g.graded = axes;
  return g;
}

/// A point well inside the grid (cells 8..15 on every axis).
Vec3 inside(const GridGeometry& g, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Vec3 x;
  for (int a = 0; a < g.dim; ++a) {
    const GradedAxis& ax = (*g.graded)[a];
    x[a] = ax.node[8] + u(rng) * (ax.node[16] - ax.node[8]);
  }
  return x;
}

template <int Dim>
void expect_complete(const GridGeometry& g, const Stencil<Dim>& s, const Vec3& x, const char* what) {
  double sum = 0.0;
  Vec3 xs, gsum;
  Mat3 gx;
  for (int k = 0; k < s.count; ++k) {
    const Index I = s.node[k];
    const int i = static_cast<int>(I % g.nodes[0]), j = static_cast<int>((I / g.nodes[0]) % g.nodes[1]);
    const int l = static_cast<int>(I / (static_cast<Index>(g.nodes[0]) * g.nodes[1]));
    const Vec3 xi = g.node_position(i, j, l);
    sum += s.w[k];
    xs += s.w[k] * xi;
    gsum += s.grad[k];
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) gx(a, b) += xi[a] * s.grad[k][b];
  }
  EXPECT_NEAR(sum, 1.0, 1e-12) << what;
  for (int a = 0; a < Dim; ++a) {
    EXPECT_NEAR(xs[a], x[a], 1e-12) << what << " axis " << a;
    EXPECT_NEAR(gsum[a], 0.0, 1e-10) << what;
    for (int b = 0; b < Dim; ++b) EXPECT_NEAR(gx(a, b), a == b ? 1.0 : 0.0, 1e-10) << what << " " << a << b;
  }
}

template <int Dim>
void check_completeness() {
  const GridGeometry g = graded_grid(Dim, false);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.05, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 x = inside(g, rng);
    Stencil<Dim> s;
    graded_linear_stencil<Dim>(g, x, s);
    expect_complete<Dim>(g, s, x, "linear");
    // GIMP half-lengths up to half the smallest cell (0.05), and beyond (clamped).
    const Vec3 lp{{u(rng) * 0.06, u(rng) * 0.06, u(rng) * 0.06}};
    graded_gimp_stencil<Dim>(g, x, lp, s);
    expect_complete<Dim>(g, s, x, "gimp");
    // CPDI: a sheared, stretched domain.
    Mat3 r;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) r(a, b) = (a == b ? 0.05 : 0.01 * (a - b)) * u(rng);
    graded_cpdi_stencil<Dim>(g, x, r, s);
    expect_complete<Dim>(g, s, x, "cpdi");
  }
}

}  // namespace

TEST(GradedShapeFunctions, PartitionOfUnityAndLinearCompletenessOnUnequalCells) {
  check_completeness<2>();
  check_completeness<3>();
}

TEST(GradedShapeFunctions, TheGimpGradientIsTheDerivativeOfItsWeight) {
  const GridGeometry g = graded_grid(2, false);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 x = inside(g, rng);
    const Vec3 lp{{0.04, 0.03, 0.0}};
    const double d = 1e-7;
    Stencil<2> s, sp, sm;
    graded_gimp_stencil<2>(g, x, lp, s);
    for (int a = 0; a < 2; ++a) {
      Vec3 xp = x, xm = x;
      xp[a] += d;
      xm[a] -= d;
      graded_gimp_stencil<2>(g, xp, lp, sp);
      graded_gimp_stencil<2>(g, xm, lp, sm);
      for (int k = 0; k < s.count; ++k) {
        auto weight = [&](const Stencil<2>& t) {
          for (int q = 0; q < t.count; ++q)
            if (t.node[q] == s.node[k]) return t.w[q];
          return 0.0;
        };
        EXPECT_NEAR((weight(sp) - weight(sm)) / (2 * d), s.grad[k][a], 1e-6) << "node " << s.node[k];
      }
    }
  }
}

TEST(GradedShapeFunctions, OnEqualCellsTheyAreTheUniformGridsWeights) {
  const GridGeometry graded = graded_grid(3, true);
  GridGeometry uniform = graded;
  uniform.graded.reset();
  std::mt19937 rng(5);
  auto same = [](const Stencil<3>& a, const Stencil<3>& b, const char* what) {
    // Entries with support in both; the uniform GIMP window may list a zero-weight end node.
    for (int k = 0; k < a.count; ++k) {
      double w = 0.0;
      Vec3 gr;
      for (int q = 0; q < b.count; ++q)
        if (b.node[q] == a.node[k]) {
          w += b.w[q];
          gr += b.grad[q];
        }
      EXPECT_NEAR(a.w[k], w, 1e-13) << what;
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(a.grad[k][d], gr[d], 1e-11) << what;
    }
  };
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 x = inside(graded, rng);
    Stencil<3> a, b;
    graded_linear_stencil<3>(graded, x, a);
    linear_stencil<3>(uniform, x, b);
    same(a, b, "linear");
    const Vec3 lp{{0.0625, 0.1, 0.125}};
    graded_gimp_stencil<3>(graded, x, lp, a);
    gimp_stencil<3>(uniform, x, lp, b);
    same(a, b, "gimp");
    same(b, a, "gimp (the other way)");
  }
}

TEST(GradedAxis, FindsTheCellOfAnyCoordinate) {
  const GradedAxis ax({0.0, 0.1, 0.3, 0.35, 0.9});
  EXPECT_EQ(ax.cell_of(0.0), 0);
  EXPECT_EQ(ax.cell_of(0.0999), 0);
  EXPECT_EQ(ax.cell_of(0.1), 1);
  EXPECT_EQ(ax.cell_of(0.34), 2);
  EXPECT_EQ(ax.cell_of(0.35), 3);
  EXPECT_EQ(ax.cell_of(0.8999), 3);
  EXPECT_EQ(ax.cell_of(0.9), 4);    // beyond the last node: the last cell's size continues
  EXPECT_EQ(ax.cell_of(1.46), 5);
  EXPECT_EQ(ax.cell_of(-0.05), -1);  // below: the first cell's size
  int c;
  double t;
  ax.locate(0.325, c, t);
  EXPECT_EQ(c, 2);
  EXPECT_NEAR(t, 0.5, 1e-14);
}

TEST(GradedShapeFunctions, ASliverOfOverlapKeepsItsWeightBesideItsGradient) {
  // A uGIMP domain of half-length l reaching r = 1e-9 past the node at 0.5 into the support of
  // the node at 0.75 (its hat rises over [0.5, 0.75], h = 0.25): S = r^2 / (4 l h), dS/dx =
  // r / (2 l h). Taken as a difference of antiderivatives the weight cancels to 0 while the
  // gradient stays: a node with a force and no mass, which blew a graded run up.
  const GradedAxis ax({0.0, 0.25, 0.5, 0.75, 1.0, 1.25});
  const double l = 0.1, r = 1e-9, h = 0.25;
  const double x = 0.5 + r - l;
  shape_detail::Axis1D<3> a;
  graded_detail::gimp_1d(ax, x, l, a);
  ASSERT_EQ(a.first, 1);  // nodes at 0.25, 0.5, 0.75
  EXPECT_NEAR(a.w[2], r * r / (4 * l * h), 1e-6 * r * r / (4 * l * h));
  EXPECT_NEAR(a.dw[2], r / (2 * l * h), 1e-6 * r / (2 * l * h));
}

}  // namespace test_graded_shape_functions
