// Program burn by Huygens' construction (points/program_burn.hpp; seed 001 "Program Burn"; issue
// 15 item 5): lighting times against their analytic answers — a planar front (x / D), a point
// detonation (|x - x_d| / D), geodesics around a circular and a rectangular obstacle, a wall the
// front cannot cross and a gap it goes through.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "core/error.hpp"
#include "points/program_burn.hpp"

namespace ballista::test_program_burn {
namespace {

constexpr double kD = 8000.0;  // m/s, a detonation speed of the order of Composition B's
constexpr double kH = 1.0e-3;  // m, lattice spacing

/// Lattice points at cell centres (i + 1/2) h of an nx x ny (x nz) block.
struct Cloud {
  std::vector<Vec3> x;
  std::vector<char> explosive;
};

Cloud lattice(int nx, int ny, int nz, const std::function<bool(const Vec3&)>& is_explosive) {
  Cloud c;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Vec3 p{{(i + 0.5) * kH, (j + 0.5) * kH, nz > 1 ? (k + 0.5) * kH : 0.0}};
        c.x.push_back(p);
        c.explosive.push_back(is_explosive(p) ? 1 : 0);
      }
  return c;
}

ProgramBurnResult burn(const Cloud& c, const std::vector<Detonator>& det, int dim) {
  ProgramBurnOptions opt;
  opt.speed = kD;
  opt.spacing = kH;
  opt.dim = dim;
  return program_burn(c.x.data(), c.explosive.data(), static_cast<Index>(c.x.size()), det, opt);
}

// A line of detonators on the face x = 0 of a 3D slab: the front is planar and each point lights
// at x / D. Graph paths along a lattice axis are exact, so the bound of one lattice spacing (the
// issue's) holds with room to spare; measured: exact to round-off.
TEST(ProgramBurn, PlanarFrontArrivesAtXOverD) {
  const Cloud c = lattice(60, 8, 8, [](const Vec3&) { return true; });
  std::vector<Detonator> det;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j) det.push_back({Vec3{{0.0, (j + 0.5) * kH, (k + 0.5) * kH}}, 0.0});
  const ProgramBurnResult r = burn(c, det, 3);
  double worst = 0.0;
  for (size_t p = 0; p < c.x.size(); ++p) worst = std::max(worst, std::abs(r.time[p] * kD - c.x[p][0]));
  std::printf("planar front: worst |t D - x| = %.3g m (spacing %.3g m)\n", worst, kH);
  EXPECT_LT(worst, kH);
  EXPECT_LT(worst, 1e-12);
  EXPECT_EQ(r.unreachable, 0);
}

// A point detonation in a 3D block: t D against |x - x_d|. The any-angle search keeps every
// path straight from the detonator in open explosive, so the times are exact to round-off (a
// plain graph search with the same edges overestimates by up to 3.6 %).
TEST(ProgramBurn, PointDetonationFollowsTheEuclideanDistance) {
  const Cloud c = lattice(24, 24, 24, [](const Vec3&) { return true; });
  const Vec3 xd{{0.5 * kH, 0.5 * kH, 0.5 * kH}};  // on a corner lattice point
  const ProgramBurnResult r = burn(c, {{xd, 1.0e-6}}, 3);
  double worst = 0.0;
  for (size_t p = 0; p < c.x.size(); ++p) {
    const double d = norm(c.x[p] - xd);
    if (d == 0.0) continue;
    worst = std::max(worst, std::abs((r.time[p] - 1.0e-6) * kD / d - 1.0));
  }
  std::printf("point detonation, 3D: worst |t D / distance - 1| = %.3g\n", worst);
  EXPECT_LT(worst, 1e-12);
}

/// Length of the shortest path from s to p around a disk (centre c, radius R) in the plane:
/// straight if the segment misses the disk, else tangent + arc + tangent.
double geodesic_around_disk(const Vec3& s, const Vec3& p, const Vec3& c, double R) {
  const Vec3 d = p - s;
  if (dot(d, d) == 0.0) return 0.0;
  const double t = std::clamp(dot(c - s, d) / dot(d, d), 0.0, 1.0);
  if (norm(s + t * d - c) >= R) return norm(d);
  const double ds = norm(s - c), dp = norm(p - c);
  const double theta = std::acos(std::clamp(dot(s - c, p - c) / (ds * dp), -1.0, 1.0));
  const double arc = theta - std::acos(R / ds) - std::acos(R / dp);
  return std::sqrt(ds * ds - R * R) + std::sqrt(dp * dp - R * R) + R * arc;
}

// A 2D charge with a circular inert inclusion (radius 25 spacings): behind it the front arrives
// along the geodesic (tangent, arc, tangent). Bound 2 % (issue 15 item 5). In open explosive the
// any-angle paths are straight (exact); the error comes from the lattice disk, whose staircase
// of inert cells sticks out up to ~0.7 spacings beyond R, so the path that hugs it is longer by
// O(h / R): 2.15 % worst at R = 15 spacings, see the printout at 25.
TEST(ProgramBurn, FrontGoesAroundACircularObstacleAlongTheGeodesic) {
  const Vec3 centre{{90.0 * kH, 60.0 * kH, 0.0}};
  const double R = 25.0 * kH;
  const Cloud c = lattice(180, 120, 1, [&](const Vec3& p) { return norm(p - centre) > R; });
  const Vec3 xd{{30.5 * kH, 60.5 * kH, 0.0}};
  const ProgramBurnResult r = burn(c, {{xd, 0.0}}, 2);
  EXPECT_EQ(r.unreachable, 0);
  double worst = 0.0;
  int shadow = 0;
  for (size_t p = 0; p < c.x.size(); ++p) {
    if (!c.explosive[p]) {
      EXPECT_TRUE(std::isinf(r.time[p]));
      continue;
    }
    const double g = geodesic_around_disk(xd, c.x[p], centre, R);
    if (g < 10.0 * kH || g <= norm(c.x[p] - xd) * (1.0 + 1e-9)) continue;  // only the shadow
    ++shadow;
    worst = std::max(worst, std::abs(r.time[p] * kD / g - 1.0));
  }
  std::printf("circular obstacle: %d shadow points, worst |t D / geodesic - 1| = %.4f\n", shadow, worst);
  EXPECT_GT(shadow, 500);
  EXPECT_LT(worst, 0.02);
}

/// Shortest path from s to p around an axis-aligned rectangle [lo, hi] (2D): the visibility graph
/// of s, p and the four corners.
double geodesic_around_box(const Vec3& s, const Vec3& p, const Vec3& lo, const Vec3& hi) {
  // Does the open segment a-b pass through the rectangle's interior? (Liang-Barsky clipping.)
  auto blocked = [&](const Vec3& a, const Vec3& b) {
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 2; ++k) {
      const double d = b[k] - a[k];
      const double e = 1e-12;
      if (std::abs(d) < 1e-300) {
        if (a[k] <= lo[k] + e || a[k] >= hi[k] - e) return false;
        continue;
      }
      double ta = (lo[k] + e - a[k]) / d, tb = (hi[k] - e - a[k]) / d;
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return t0 < t1;
  };
  std::vector<Vec3> v = {s, Vec3{{lo[0], lo[1], 0}}, Vec3{{hi[0], lo[1], 0}}, Vec3{{hi[0], hi[1], 0}},
                         Vec3{{lo[0], hi[1], 0}}, p};
  std::vector<double> dist(v.size(), std::numeric_limits<double>::infinity());
  std::vector<char> done(v.size(), 0);
  dist[0] = 0.0;
  for (size_t it = 0; it < v.size(); ++it) {
    size_t u = v.size();
    for (size_t i = 0; i < v.size(); ++i)
      if (!done[i] && (u == v.size() || dist[i] < dist[u])) u = i;
    done[u] = 1;
    for (size_t w = 0; w < v.size(); ++w)
      if (!done[w] && !blocked(v[u], v[w])) dist[w] = std::min(dist[w], dist[u] + norm(v[w] - v[u]));
  }
  return dist.back();
}

// A rectangular inert block (20 x 30 spacings, its faces on cell faces): the front bends around
// its corners. The lattice path bends half a spacing off each corner, so the excess is the
// metric's 1.31 % plus O(h / path); bound 2 %.
TEST(ProgramBurn, FrontGoesAroundARectangularObstacle) {
  const Vec3 lo{{50.0 * kH, 25.0 * kH, 0.0}}, hi{{70.0 * kH, 55.0 * kH, 0.0}};
  auto inside = [&](const Vec3& p) { return p[0] > lo[0] && p[0] < hi[0] && p[1] > lo[1] && p[1] < hi[1]; };
  const Cloud c = lattice(120, 80, 1, [&](const Vec3& p) { return !inside(p); });
  const Vec3 xd{{30.5 * kH, 40.5 * kH, 0.0}};
  const ProgramBurnResult r = burn(c, {{xd, 0.0}}, 2);
  double worst = 0.0;
  int shadow = 0;
  for (size_t p = 0; p < c.x.size(); ++p) {
    if (!c.explosive[p]) continue;
    const double g = geodesic_around_box(xd, c.x[p], lo, hi);
    if (g < 10.0 * kH || g <= norm(c.x[p] - xd) * (1.0 + 1e-9)) continue;
    ++shadow;
    worst = std::max(worst, std::abs(r.time[p] * kD / g - 1.0));
  }
  std::printf("rectangular obstacle: %d shadow points, worst |t D / geodesic - 1| = %.4f\n", shadow, worst);
  EXPECT_GT(shadow, 500);
  EXPECT_LT(worst, 0.02);
}

// An inert wall one spacing thick across the charge: no graph edge may jump it (edges reach 3.2
// spacings, so only the line-of-sight test stops them). With a gap the front passes through it.
TEST(ProgramBurn, AWallStopsTheFrontAndAGapLetsItThrough) {
  auto wall = [](bool gap) {
    return [gap](const Vec3& p) {
      const bool in_wall = p[0] > 30.0 * kH && p[0] < 31.0 * kH;
      const bool in_gap = gap && p[1] > 36.0 * kH && p[1] < 40.0 * kH;
      return !in_wall || in_gap;
    };
  };
  const Vec3 xd{{10.5 * kH, 20.5 * kH, 0.0}};
  const Cloud closed = lattice(60, 40, 1, wall(false));
  const ProgramBurnResult rc = burn(closed, {{xd, 0.0}}, 2);
  EXPECT_EQ(rc.unreachable, 29 * 40);  // everything beyond the wall (x > 31 h)
  const Cloud open = lattice(60, 40, 1, wall(true));
  const ProgramBurnResult ro = burn(open, {{xd, 0.0}}, 2);
  EXPECT_EQ(ro.unreachable, 0);
  // Beyond the wall the path goes through the gap: longer than the straight line.
  for (size_t p = 0; p < open.x.size(); ++p)
    if (open.x[p][0] > 31.0 * kH && open.x[p][1] < 30.0 * kH) {
      EXPECT_GT(ro.time[p] * kD, norm(open.x[p] - xd) * 1.05);
    }
}

// Inert points on another lattice (offset by half a spacing, e.g. a body with another
// particles_per_cell) beside the charge: the occupancy cells follow the explosive's own lattice,
// so the front is unaffected (planar, exact); the same explosive points alone give the same times.
TEST(ProgramBurn, InertPointsOnAnotherLatticeDoNotDisturbTheCharge) {
  Cloud c = lattice(30, 6, 1, [](const Vec3&) { return true; });
  const Cloud alone = c;
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 8; ++i) {  // an inert plate below x = 0 at half the spacing, shifted
      c.x.push_back(Vec3{{-(i + 0.25) * 0.5 * kH, (j + 0.25) * 0.5 * kH, 0.0}});
      c.explosive.push_back(0);
    }
  std::vector<Detonator> det;
  for (int j = 0; j < 6; ++j) det.push_back({Vec3{{0.0, (j + 0.5) * kH, 0.0}}, 0.0});
  const ProgramBurnResult r = burn(c, det, 2), r0 = burn(alone, det, 2);
  for (size_t p = 0; p < alone.x.size(); ++p) {
    EXPECT_EQ(r.time[p], r0.time[p]);
    EXPECT_NEAR(r.time[p] * kD, alone.x[p][0], 1e-12);
  }
}

TEST(ProgramBurn, ADetonatorAwayFromTheChargeIsAnError) {
  const Cloud c = lattice(10, 10, 1, [](const Vec3&) { return true; });
  try {
    burn(c, {{Vec3{{0.1, 0.1, 0.0}}, 0.0}}, 2);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("detonation point 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ballista::test_program_burn
