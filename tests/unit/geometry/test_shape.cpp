// Shape membership and bounding boxes against the definitions of docs/deck.md ("Shapes"):
// boundaries are inclusive, a cylinder's centre is the centre of its base and it extends by
// `length` along +axis, in 2D a cylinder across z is a disk, along x or y it is the rectangle of
// its axial section (plane strain) or the r-z half plane (axisymmetric, centre x = 0).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "geometry/shape.hpp"

namespace test_shape {

using namespace ballista;

namespace {

ShapeSpec box(Vec3 lo, Vec3 hi) {
  ShapeSpec s;
  s.type = "box";
  s.lower = lo;
  s.upper = hi;
  return s;
}
ShapeSpec sphere(Vec3 c, double r) {
  ShapeSpec s;
  s.type = "sphere";
  s.center = c;
  s.radius = r;
  return s;
}
ShapeSpec cylinder(Vec3 c, int axis, double r, double len, double inner = 0.0) {
  ShapeSpec s;
  s.type = inner > 0.0 ? "tube" : "cylinder";
  s.center = c;
  s.axis = axis;
  s.radius = r;
  s.length = len;
  s.inner_radius = inner;
  return s;
}
Vec3 unit(int a) {
  Vec3 e;
  e[a] = 1.0;
  return e;
}

constexpr double kIn = 1.0 - 1e-9;   // relative position just inside a boundary
constexpr double kOut = 1.0 + 1e-9;  // just outside

}  // namespace

TEST(Shape, BoxIsClosedAndAxisAligned) {
  const ShapeSpec s = box({{-1.0, 2.0, 3.0}}, {{1.0, 4.0, 7.0}});
  EXPECT_TRUE(shape_contains(s, {{0.0, 3.0, 5.0}}, 3));
  EXPECT_TRUE(shape_contains(s, {{-1.0, 2.0, 3.0}}, 3));  // corners included
  EXPECT_TRUE(shape_contains(s, {{1.0, 4.0, 7.0}}, 3));
  for (int a = 0; a < 3; ++a) {
    Vec3 lo_out{{0.0, 3.0, 5.0}}, hi_out{{0.0, 3.0, 5.0}};
    lo_out[a] = s.lower[a] - 1e-9;
    hi_out[a] = s.upper[a] + 1e-9;
    EXPECT_FALSE(shape_contains(s, lo_out, 3)) << a;
    EXPECT_FALSE(shape_contains(s, hi_out, 3)) << a;
  }
  // 2D ignores z entirely.
  EXPECT_TRUE(shape_contains(s, {{0.0, 3.0, 100.0}}, 2));
  Vec3 lo, hi;
  shape_bounds(s, 3, lo, hi);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(lo[a], s.lower[a]);
    EXPECT_EQ(hi[a], s.upper[a]);
  }
  shape_bounds(s, 2, lo, hi);
  EXPECT_EQ(lo[2], 0.0);
  EXPECT_EQ(hi[2], 0.0);
}

TEST(Shape, SphereAndDisk) {
  const Vec3 c{{0.3, -0.2, 0.5}};
  const double r = 0.7;
  const ShapeSpec s = sphere(c, r);
  const Vec3 d = (1.0 / std::sqrt(3.0)) * Vec3{{1.0, -1.0, 1.0}};
  EXPECT_TRUE(shape_contains(s, c + (kIn * r) * d, 3));
  EXPECT_FALSE(shape_contains(s, c + (kOut * r) * d, 3));
  // 2D: a disk in the x-y plane; z is ignored.
  const Vec3 d2{{0.6, 0.8, 0.0}};
  EXPECT_TRUE(shape_contains(s, c + (kIn * r) * d2 + Vec3{{0.0, 0.0, 9.0}}, 2));
  EXPECT_FALSE(shape_contains(s, c + (kOut * r) * d2, 2));
  Vec3 lo, hi;
  shape_bounds(s, 3, lo, hi);
  for (int a = 0; a < 3; ++a) {
    EXPECT_DOUBLE_EQ(lo[a], c[a] - r);
    EXPECT_DOUBLE_EQ(hi[a], c[a] + r);
  }
}

TEST(Shape, CylinderAndTubeIn3dForEveryAxis) {
  const Vec3 c{{0.1, 0.2, 0.3}};
  const double R = 0.5, L = 2.0, Ri = 0.2;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, bb = (a + 2) % 3;
    const Vec3 e = unit(a), n = (1.0 / std::sqrt(2.0)) * (unit(b) + unit(bb));
    const ShapeSpec cyl = cylinder(c, a, R, L);
    // The centre is the centre of the base: the body spans [c, c + L e].
    EXPECT_TRUE(shape_contains(cyl, c, 3)) << a;
    EXPECT_TRUE(shape_contains(cyl, c + L * e, 3)) << a;
    EXPECT_TRUE(shape_contains(cyl, c + (0.5 * L) * e + (kIn * R) * n, 3)) << a;
    EXPECT_FALSE(shape_contains(cyl, c + (0.5 * L) * e + (kOut * R) * n, 3)) << a;
    EXPECT_FALSE(shape_contains(cyl, c + (-1e-9) * e, 3)) << a;
    EXPECT_FALSE(shape_contains(cyl, c + (L + 1e-9) * e, 3)) << a;
    // Points off the axis in the axial coordinate only are inside (no sphere-like cut).
    EXPECT_TRUE(shape_contains(cyl, c + (0.999 * L) * e + (0.99 * R) * unit(b), 3)) << a;
    const ShapeSpec tube = cylinder(c, a, R, L, Ri);
    EXPECT_FALSE(shape_contains(tube, c + (0.5 * L) * e, 3)) << a;  // the bore
    EXPECT_FALSE(shape_contains(tube, c + (0.5 * L) * e + (Ri * (1.0 - 1e-9)) * n, 3)) << a;
    EXPECT_TRUE(shape_contains(tube, c + (0.5 * L) * e + (Ri * kOut) * n, 3)) << a;
    EXPECT_TRUE(shape_contains(tube, c + (0.5 * L) * e + (kIn * R) * n, 3)) << a;
    Vec3 lo, hi;
    shape_bounds(cyl, 3, lo, hi);
    EXPECT_DOUBLE_EQ(lo[a], c[a]);
    EXPECT_DOUBLE_EQ(hi[a], c[a] + L);
    EXPECT_DOUBLE_EQ(lo[b], c[b] - R);
    EXPECT_DOUBLE_EQ(hi[b], c[b] + R);
    EXPECT_DOUBLE_EQ(lo[bb], c[bb] - R);
    EXPECT_DOUBLE_EQ(hi[bb], c[bb] + R);
  }
}

TEST(Shape, TwoDimensionalDiskAndAnnulus) {
  const Vec3 c{{0.4, -0.3, 0.0}};
  const ShapeSpec disk = cylinder(c, 2, 1.0, 0.0);
  const Vec3 n{{0.6, -0.8, 0.0}};
  EXPECT_TRUE(shape_contains(disk, c + kIn * n, 2));
  EXPECT_FALSE(shape_contains(disk, c + kOut * n, 2));
  const ShapeSpec ring = cylinder(c, 2, 1.0, 0.0, 0.5);
  EXPECT_FALSE(shape_contains(ring, c + 0.49 * n, 2));
  EXPECT_TRUE(shape_contains(ring, c + 0.51 * n, 2));
  Vec3 lo, hi;
  shape_bounds(disk, 2, lo, hi);
  EXPECT_DOUBLE_EQ(lo[0], c[0] - 1.0);
  EXPECT_DOUBLE_EQ(hi[1], c[1] + 1.0);
}

TEST(Shape, AxisymmetricCylinderIsTheRzRectangle) {
  // Axisymmetric decks: axis y, centre x = 0; the shape is 0 <= r <= R, y0 <= y <= y0 + L.
  const ShapeSpec cyl = cylinder({{0.0, 0.25, 0.0}}, 1, 0.5, 1.0);
  EXPECT_TRUE(shape_contains(cyl, {{0.0, 0.25, 0.0}}, 2));
  EXPECT_TRUE(shape_contains(cyl, {{0.5 * kIn, 1.25, 0.0}}, 2));
  EXPECT_FALSE(shape_contains(cyl, {{0.5 * kOut, 0.5, 0.0}}, 2));
  EXPECT_FALSE(shape_contains(cyl, {{0.2, 0.25 - 1e-9, 0.0}}, 2));
  EXPECT_FALSE(shape_contains(cyl, {{0.2, 1.25 + 1e-9, 0.0}}, 2));
  const ShapeSpec tube = cylinder({{0.0, 0.0, 0.0}}, 1, 0.5, 1.0, 0.3);
  EXPECT_FALSE(shape_contains(tube, {{0.29, 0.5, 0.0}}, 2));
  EXPECT_TRUE(shape_contains(tube, {{0.31, 0.5, 0.0}}, 2));
  Vec3 lo, hi;
  shape_bounds(cyl, 2, lo, hi);
  EXPECT_LE(lo[0], 0.0);  // covers the whole radial range [0, R]
  EXPECT_DOUBLE_EQ(hi[0], 0.5);
  EXPECT_DOUBLE_EQ(lo[1], 0.25);
  EXPECT_DOUBLE_EQ(hi[1], 1.25);
}

TEST(Shape, PlaneStrainCylinderAlongXOrYIsItsAxialSection) {
  // docs/deck.md: in plane strain a cylinder with axis x or y is the rectangle of its axial
  // section: along the axis [c, c + L], across it [c - R, c + R], wherever the centre is.
  const Vec3 c{{0.7, -0.4, 0.0}};
  const double R = 0.2, L = 1.0;
  const ShapeSpec along_x = cylinder(c, 0, R, L);
  EXPECT_TRUE(shape_contains(along_x, c + Vec3{{0.5, 0.0, 0.0}}, 2));
  EXPECT_TRUE(shape_contains(along_x, c + Vec3{{0.5, kIn * R, 0.0}}, 2));
  EXPECT_TRUE(shape_contains(along_x, c + Vec3{{0.5, -kIn * R, 0.0}}, 2));
  EXPECT_FALSE(shape_contains(along_x, c + Vec3{{0.5, kOut * R, 0.0}}, 2));
  EXPECT_FALSE(shape_contains(along_x, c + Vec3{{-1e-9, 0.0, 0.0}}, 2));
  EXPECT_FALSE(shape_contains(along_x, c + Vec3{{L + 1e-9, 0.0, 0.0}}, 2));
  const ShapeSpec along_y = cylinder(c, 1, R, L);
  EXPECT_TRUE(shape_contains(along_y, c + Vec3{{0.0, 0.5, 0.0}}, 2));
  EXPECT_TRUE(shape_contains(along_y, c + Vec3{{-kIn * R, 0.5, 0.0}}, 2));
  EXPECT_FALSE(shape_contains(along_y, c + Vec3{{kOut * R, 0.5, 0.0}}, 2));
  EXPECT_FALSE(shape_contains(along_y, {{0.0, c[1] + 0.5, 0.0}}, 2));  // x = 0 is far outside
  Vec3 lo, hi;
  shape_bounds(along_x, 2, lo, hi);
  EXPECT_DOUBLE_EQ(lo[0], c[0]);
  EXPECT_DOUBLE_EQ(hi[0], c[0] + L);
  EXPECT_DOUBLE_EQ(lo[1], c[1] - R);
  EXPECT_DOUBLE_EQ(hi[1], c[1] + R);
  shape_bounds(along_y, 2, lo, hi);
  EXPECT_DOUBLE_EQ(lo[0], c[0] - R);
  EXPECT_DOUBLE_EQ(hi[0], c[0] + R);
  EXPECT_DOUBLE_EQ(lo[1], c[1]);
  EXPECT_DOUBLE_EQ(hi[1], c[1] + L);
}

TEST(Shape, BoundsContainEveryInsidePoint) {
  // Property: for random points, contained => within the bounding box (seeding relies on it).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const ShapeSpec shapes[] = {
      box({{-0.5, -0.2, 0.1}}, {{0.3, 0.9, 1.1}}), sphere({{0.2, -0.1, 0.3}}, 0.8),
      cylinder({{0.1, 0.2, -0.3}}, 0, 0.6, 1.2), cylinder({{0.1, 0.2, -0.3}}, 1, 0.6, 1.2),
      cylinder({{0.1, 0.2, -0.3}}, 2, 0.6, 1.2), cylinder({{0.3, -0.5, 0.0}}, 1, 0.9, 1.0, 0.4)};
  for (int dim : {2, 3})
    for (const auto& s : shapes) {
      Vec3 lo, hi;
      shape_bounds(s, dim, lo, hi);
      int inside = 0;
      for (int k = 0; k < 4000; ++k) {
        const Vec3 x{{u(rng), u(rng), dim == 3 ? u(rng) : 0.0}};
        if (!shape_contains(s, x, dim)) continue;
        ++inside;
        for (int a = 0; a < dim; ++a) {
          EXPECT_GE(x[a], lo[a]) << s.type << " axis " << s.axis << " dim " << dim;
          EXPECT_LE(x[a], hi[a]) << s.type << " axis " << s.axis << " dim " << dim;
        }
      }
      EXPECT_GT(inside, 20) << s.type;  // the property was actually exercised
    }
}

TEST(Shape, UnknownTypeIsAnError) {
  ShapeSpec s;
  s.type = "pyramid";
  EXPECT_THROW(shape_contains(s, Vec3{}, 3), Error);
}

TEST(Shape, LatticePointsOnAFaceAreInsideWhateverTheirRoundOff) {
  // The lattice of the Kalthoff-Winkler deck at 2 mm: y_k = -0.104 + (k + 1/2) 0.002 puts points
  // exactly on the faces y = -0.025 (k = 39) and y = 0.025 (k = 64) in exact arithmetic; their
  // computed coordinates miss the faces by round-off, one on each side. Both rows must be inside
  // (a symmetric body stays symmetric), and so must the rows on a sphere's and a cylinder's surface.
  ShapeSpec box;
  box.type = "box";
  box.lower = Vec3{{-1.0, -0.025, -1.0}};
  box.upper = Vec3{{1.0, 0.025, 1.0}};
  int inside = 0;
  for (int k = 0; k < 104; ++k) inside += shape_contains(box, Vec3{{0.0, -0.104 + (k + 0.5) * 0.002, 0.0}}, 3);
  EXPECT_EQ(inside, 26);  // k = 39 ... 64
  // A point a thousandth of a spacing outside is still outside (the tolerance is 1e-12 of the size).
  EXPECT_FALSE(shape_contains(box, Vec3{{0.0, 0.025 + 2e-6, 0.0}}, 3));
  ShapeSpec sphere;
  sphere.type = "sphere";
  sphere.center = Vec3{{0.1, 0.0, 0.0}};
  sphere.radius = 0.3;
  EXPECT_TRUE(shape_contains(sphere, Vec3{{0.4, 0.0, 0.0}}, 3));  // (0.4 - 0.1)^2 > 0.3^2 in binary
  EXPECT_FALSE(shape_contains(sphere, Vec3{{0.4 + 1e-6, 0.0, 0.0}}, 3));
}

// shape_depth: the distance to the nearest face inside (exact for these convex shapes and the
// tube's wall), negative outside, so that overlap checks can ignore points on a shared face.
TEST(Shape, DepthIsTheDistanceToTheNearestFaceInsideAndNegativeOutside) {
  const ShapeSpec b = box({{0.0, 0.0, 0.0}}, {{2.0, 4.0, 6.0}});
  EXPECT_DOUBLE_EQ(shape_depth(b, {{1.0, 2.0, 3.0}}, 3), 1.0);
  EXPECT_DOUBLE_EQ(shape_depth(b, {{0.25, 2.0, 3.0}}, 3), 0.25);
  EXPECT_DOUBLE_EQ(shape_depth(b, {{1.0, 2.0, 6.0}}, 3), 0.0);  // on a face
  EXPECT_LT(shape_depth(b, {{3.0, 2.0, 3.0}}, 3), 0.0);
  EXPECT_DOUBLE_EQ(shape_depth(b, {{1.0, 3.5, 100.0}}, 2), 0.5);  // 2D ignores z
  const ShapeSpec s = sphere({{1.0, 1.0, 1.0}}, 2.0);
  EXPECT_DOUBLE_EQ(shape_depth(s, {{1.0, 1.0, 2.5}}, 3), 0.5);
  EXPECT_DOUBLE_EQ(shape_depth(s, {{1.0, 1.0, 4.0}}, 3), -1.0);
  const ShapeSpec t = cylinder({{0.0, 0.0, 0.0}}, 2, 2.0, 10.0, 1.0);  // tube 1 < r < 2, 0 < z < 10
  EXPECT_DOUBLE_EQ(shape_depth(t, {{1.25, 0.0, 5.0}}, 3), 0.25);
  EXPECT_DOUBLE_EQ(shape_depth(t, {{1.5, 0.0, 0.2}}, 3), 0.2);
  EXPECT_LT(shape_depth(t, {{0.5, 0.0, 5.0}}, 3), 0.0);  // in the bore
  EXPECT_DOUBLE_EQ(shape_depth(t, {{0.0, 1.5, 1e9}}, 2), 0.5);  // a 2D annulus has no length
  const ShapeSpec axi = cylinder({{0.0, 1.0, 0.0}}, 1, 3.0, 4.0);  // r-z rectangle 0 < r < 3, 1 < z < 5
  EXPECT_DOUBLE_EQ(shape_depth(axi, {{2.5, 3.0, 0.0}}, 2), 0.5);
  EXPECT_DOUBLE_EQ(shape_depth(axi, {{1.0, 1.25, 0.0}}, 2), 0.25);
}

}  // namespace test_shape
