// The family size the memory estimate counts (pd::lattice_family_size) against the lattice-point
// counts of the sphere and the circle (Gauss's circle problem: N(3) = 29 points of Z^2 within
// radius 3, 123 of Z^3, the origin included) and against the continuum count for large horizons.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "peridynamics/bond_family.hpp"

namespace test_bond_family_size {

using namespace ballista;

TEST(BondFamilySize, CountsTheLatticePointsWithinTheHorizon) {
  EXPECT_EQ(pd::lattice_family_size(3.0, 3), 122.0);
  EXPECT_EQ(pd::lattice_family_size(3.0, 2), 28.0);
  EXPECT_EQ(pd::lattice_family_size(1.0, 3), 6.0);  // the faces' neighbours
  EXPECT_EQ(pd::lattice_family_size(1.0, 2), 4.0);
  EXPECT_EQ(pd::lattice_family_size(1.5, 3), 18.0);  // faces and edges: |xi|^2 = 1, 2
  // A 2D horizon of 20 spacings holds about pi 20^2 = 1257 (Gauss: within 2 % here); the 3D
  // count of the same m is 27 times larger, which is what the old estimate took for a 2D run.
  EXPECT_NEAR(pd::lattice_family_size(20.0, 2), std::numbers::pi * 400.0, 0.02 * std::numbers::pi * 400.0);
  EXPECT_NEAR(pd::lattice_family_size(100.0, 3) / (4.0 / 3.0 * std::numbers::pi * 1e6), 1.0, 0.01);
  EXPECT_EQ(pd::lattice_family_size(500.0, 2), std::numbers::pi * 250000.0);  // the continuum count
  EXPECT_EQ(pd::lattice_family_size(0.5, 3), 0.0);                              // no family
  EXPECT_EQ(pd::lattice_family_size(std::nan(""), 3), 0.0);
}

}  // namespace test_bond_family_size
