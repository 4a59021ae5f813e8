// The solid bounded by a triangle surface (geometry/surface_solid.hpp) against closed forms: a box
// and a sphere's inscribed polyhedron contain exactly the points the analytic solids contain
// (away from the facets), whatever the winding; a surface with one facet missing still does, by
// the majority of the three rays; closure counts the open edges.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "geometry/surface_solid.hpp"
#include "support/surface_files.hpp"

namespace test_surface_solid {

using namespace ballista;

namespace {

TriangleSurface surface_of(const std::vector<test::Triangle>& tris, bool flip = false) {
  TriangleSurface s;
  std::map<std::array<double, 3>, int> index;  // the corners are exact copies: weld by value
  for (const auto& t : tris) {
    std::array<int, 3> f{};
    for (int c = 0; c < 3; ++c) {
      const Vec3& p = t[flip ? 2 - c : c];
      const auto [it, added] = index.try_emplace({p[0], p[1], p[2]}, static_cast<int>(s.vertices.size()));
      if (added) s.vertices.push_back(p);
      f[c] = it->second;
    }
    s.triangles.push_back(f);
  }
  return s;
}

/// Random points in [lo - pad, hi + pad] (a fixed seed: the test is deterministic).
std::vector<Vec3> samples(const Vec3& lo, const Vec3& hi, double pad, int n) {
  std::mt19937_64 rng(42);
  std::vector<Vec3> p;
  for (int k = 0; k < n; ++k) {
    Vec3 x;
    for (int d = 0; d < 3; ++d)
      x[d] = std::uniform_real_distribution<double>(lo[d] - pad, hi[d] + pad)(rng);
    p.push_back(x);
  }
  return p;
}

bool in_box(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  for (int d = 0; d < 3; ++d)
    if (x[d] < lo[d] || x[d] > hi[d]) return false;
  return true;
}

const Vec3 kLo{{0.1, -0.2, 0.3}}, kHi{{0.7, 0.5, 0.45}};

}  // namespace

TEST(SurfaceSolid, BoxContainsExactlyTheBoxEitherWinding) {
  for (bool flip : {false, true}) {
    const SurfaceSolid box(surface_of(test::box_triangles(kLo, kHi), flip));
    int inside = 0;
    for (const Vec3& x : samples(kLo, kHi, 0.1, 20000)) {
      ASSERT_EQ(box.contains(x), in_box(x, kLo, kHi)) << x[0] << " " << x[1] << " " << x[2];
      inside += in_box(x, kLo, kHi);
    }
    EXPECT_GT(inside, 5000);  // the sample tests both sides
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(box.lower()[d], kLo[d]);
      EXPECT_EQ(box.upper()[d], kHi[d]);
    }
  }
}

TEST(SurfaceSolid, LatticePointsOnFaceLinesAreDecidedOneWay) {
  // Points on the lines where faces and triangle diagonals meet (x or y equal to a face's
  // coordinate) are where a ray could hit two triangles' shared edge: each point must be counted
  // once, so the box's interior lattice is found whole.
  const Vec3 lo{{0, 0, 0}}, hi{{1, 1, 1}};
  const SurfaceSolid box(surface_of(test::box_triangles(lo, hi)));
  int inside = 0;
  for (int i = 1; i < 8; ++i)
    for (int j = 1; j < 8; ++j)
      for (int k = 1; k < 8; ++k) inside += box.contains({{i / 8.0, j / 8.0, k / 8.0}});
  EXPECT_EQ(inside, 7 * 7 * 7);
}

TEST(SurfaceSolid, IcosphereContainsTheInscribedBallAndNothingOutsideTheSphere) {
  const Vec3 c{{0.2, 0.1, -0.3}};
  const double r = 0.25;
  const SurfaceSolid ball(surface_of(test::icosphere_triangles(c, r, 3)));  // 1280 facets
  // Facets of a level-3 icosphere span at most ~0.11 rad, so the polyhedron holds the ball of
  // radius r cos(0.11) > 0.99 r and lies within the sphere of radius r.
  for (const Vec3& x : samples(c - Vec3{{r, r, r}}, c + Vec3{{r, r, r}}, 0.05, 20000)) {
    const double d = norm(x - c);
    if (d < 0.99 * r) {
      ASSERT_TRUE(ball.contains(x)) << d / r;
    }
    if (d > r) {
      ASSERT_FALSE(ball.contains(x)) << d / r;
    }
  }
}

TEST(SurfaceSolid, AMissingFacetIsOutvotedAndCountedAsOpen) {
  auto tris = test::box_triangles(kLo, kHi);
  tris.erase(tris.begin() + 10);  // one triangle of the +x face
  const TriangleSurface s = surface_of(tris);
  const SurfaceClosure closure = surface_closure(s);
  EXPECT_EQ(closure.edges, 18);  // a box of 12 triangles: 12 face edges + 6 diagonals
  EXPECT_EQ(closure.open_edges, 3);
  EXPECT_EQ(closure.non_manifold_edges, 0);
  EXPECT_EQ(closure.open_edge_at[0], kHi[0]);  // the hole is in the +x face
  const SurfaceSolid holed(s);
  for (const Vec3& x : samples(kLo, kHi, 0.1, 20000)) ASSERT_EQ(holed.contains(x), in_box(x, kLo, kHi));
}

TEST(SurfaceSolid, AClosedSurfaceHasNoOpenEdge) {
  const SurfaceClosure c = surface_closure(surface_of(test::icosphere_triangles({{0, 0, 0}}, 1.0, 2)));
  EXPECT_EQ(c.open_edges, 0);
  EXPECT_EQ(c.non_manifold_edges, 0);
  EXPECT_EQ(c.edges, 320 * 3 / 2);  // every edge shared by two of the 320 facets
}

}  // namespace test_surface_solid
