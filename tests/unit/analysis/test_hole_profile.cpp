// The wall of a hole (analysis/hole_profile.hpp) on known geometries: a plate with a hole of
// radius R, with and without crushed debris lying in the hole (a tenth of the hole's volume in
// loose points), in the three lateral geometries. The wall must be found within one annulus of R
// (the annuli are the resolution of the measurement), and the debris must not close the hole.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "analysis/hole_profile.hpp"

namespace test_hole_profile {

using namespace ballista;

namespace {

constexpr double kS = 0.25e-3;  // lattice spacing of the plate's points, m
constexpr double kR = 3.1e-3;   // hole radius (not a multiple of the spacing), m
constexpr double kOut = 12.0e-3, kThick = 4.0e-3;

/// Points of a plate 0 <= axial < kThick, kR <= r < kOut on the lattice of the geometry, plus,
/// with `debris`, loose points filling a tenth of the hole's volume at random inside it.
std::vector<LateralPoint> plate(LateralGeometry g, bool debris) {
  std::vector<LateralPoint> pts;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double z = 0.5 * kS; z < kThick; z += kS) {
    if (g == LateralGeometry::ThreeD) {
      for (double x = -kOut + 0.5 * kS; x < kOut; x += kS)
        for (double y = -kOut + 0.5 * kS; y < kOut; y += kS) {
          const double r = std::hypot(x, y);
          const bool solid = r >= kR && r < kOut;
          if (solid || (debris && r < kR && u(rng) < 0.1)) pts.push_back({z, r, kS * kS * kS, 0.5 * kS});
        }
    } else {
      for (double x = (g == LateralGeometry::PlaneStrain ? -kOut : 0.0) + 0.5 * kS; x < kOut; x += kS) {
        const double r = std::abs(x);
        const double vol = g == LateralGeometry::Axisymmetric ? r * kS * kS : kS * kS;
        const bool solid = r >= kR && r < kOut;
        if (solid || (debris && r < kR && u(rng) < 0.1)) pts.push_back({z, r, vol, 0.5 * kS});
      }
    }
  }
  return pts;
}

}  // namespace

TEST(HoleProfile, TheWallOfAHoleIsFoundWithinOneAnnulusWithOrWithoutDebris) {
  for (const LateralGeometry g : {LateralGeometry::Axisymmetric, LateralGeometry::ThreeD, LateralGeometry::PlaneStrain})
    for (const bool debris : {false, true})
      for (const double dr : {kS, 2 * kS, 0.5 * kS}) {
        const std::vector<double> w = wall_radii(plate(g, debris), 0.0, kThick, 4, g, {dr});
        for (double r : w) EXPECT_NEAR(r, kR, dr) << "geometry " << static_cast<int>(g) << " debris " << debris << " dr " << dr;
      }
}

TEST(HoleProfile, DenseMaterialOnTheAxisClosesTheHoleAndNothingIsNoWall) {
  // A solid disk (no hole): the wall is at the axis. No points in a bin: NaN.
  std::vector<LateralPoint> disk;
  for (double z = 0.5 * kS; z < kThick; z += kS)
    for (double r = 0.5 * kS; r < kOut; r += kS) disk.push_back({z, r, r * kS * kS, 0.5 * kS});
  const std::vector<double> w = wall_radii(disk, 0.0, 2 * kThick, 2, LateralGeometry::Axisymmetric, {kS});
  EXPECT_EQ(w[0], 0.0);
  EXPECT_TRUE(std::isnan(w[1]));
}

}  // namespace test_hole_profile
