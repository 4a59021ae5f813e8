// The PMB bond constants (peridynamics/bond_constants.hpp) against their closed forms: the
// continuum micromodulus c = 18 K/(pi delta^4) and critical stretch s00 = sqrt(5 G0/(9 K delta))
// (Silling & Askari 2005 eqs. 22 and 25), the 2D moduli from E and nu, the series bond of two
// materials, the yield stretch of the softest solid, and the surface correction's factors on a
// lattice cube (1 inside, larger at a face and larger still at a corner).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "peridynamics/bond_constants.hpp"

namespace test_bond_constants {

using namespace ballista;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST(BondConstants, ContinuumCalibrationGivesSillingAskari) {
  const double delta = 3e-3, K = 140e9, G0 = 2e4;
  const pd::LatticeMoments m = pd::calibration_moments(false, delta, 1e-3, true, 3);
  EXPECT_DOUBLE_EQ(m.m1, std::numbers::pi * std::pow(delta, 4));
  EXPECT_DOUBLE_EQ(m.m2, std::numbers::pi * std::pow(delta, 5) / 5.0);
  const double c = pd::micromodulus(K, m.m1, 3);
  EXPECT_NEAR(c, 18.0 * K / (std::numbers::pi * std::pow(delta, 4)), 1e-12 * c);
  const double s00 = pd::critical_stretch(std::nullopt, G0, c, m.m2);
  EXPECT_NEAR(s00, std::sqrt(5.0 * G0 / (9.0 * K * delta)), 1e-12 * s00);
  // 2D per unit thickness (Ha & Bobaru 2010): m1 = 2 pi delta^3/3, m2 = delta^4/2.
  const pd::LatticeMoments m2d = pd::calibration_moments(false, delta, 1e-3, true, 2);
  EXPECT_DOUBLE_EQ(m2d.m1, 2.0 * std::numbers::pi * std::pow(delta, 3) / 3.0);
  EXPECT_DOUBLE_EQ(m2d.m2, std::pow(delta, 4) / 2.0);
}

TEST(BondConstants, LatticeCalibrationTakesTheLatticeMoments) {
  for (int dim : {2, 3}) {
    const pd::LatticeMoments a = pd::calibration_moments(true, 3e-3, 1e-3, true, dim);
    const pd::LatticeMoments b = pd::lattice_moments(3e-3, 1e-3, true, dim);
    EXPECT_EQ(a.m1, b.m1);
    EXPECT_EQ(a.m2, b.m2);
  }
}

TEST(BondConstants, CriticalStretchGivenFromFractureEnergyOrNone) {
  EXPECT_EQ(pd::critical_stretch(0.01, std::nullopt, 1e20, 1e-12), 0.01);
  EXPECT_DOUBLE_EQ(pd::critical_stretch(std::nullopt, 8.0, 4.0, 1.0), 2.0);  // sqrt(2 G0/(c m2))
  EXPECT_TRUE(std::isinf(pd::critical_stretch(std::nullopt, std::nullopt, 1e20, 1e-12)));
}

// Micro-plastic bonds (elastic to s_y, flat beyond) break when the work done on them reaches the
// fracture energy: m2 times the integral of the bond force c min(s, s_y) from 0 to s00, integrated
// here by the midpoint rule (2e5 intervals: error ~1e-10) against the closed form's s00; a bond
// that breaks before it yields keeps the elastic rule, and the two agree where they meet.
TEST(BondConstants, MicroPlasticBondsBreakWhenTheirWorkIsTheFractureEnergy) {
  const double c = 4.0, m2 = 1.0, sy = 0.5, G0 = 8.0;
  const double s00 = pd::critical_stretch(std::nullopt, G0, c, m2, sy);
  EXPECT_DOUBLE_EQ(s00, 8.0 / (4.0 * 0.5) + 0.25);
  const int n = 200000;
  double work = 0.0;
  for (int i = 0; i < n; ++i) work += c * std::min((i + 0.5) * s00 / n, sy) * s00 / n;
  EXPECT_NEAR(m2 * work / G0, 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(pd::critical_stretch(std::nullopt, 0.2, c, m2, sy), std::sqrt(0.1));  // 0.316 < s_y
  const double meet = c * m2 * sy * sy / 2.0;
  EXPECT_NEAR(pd::critical_stretch(std::nullopt, meet * (1 + 1e-12), c, m2, sy), sy, 1e-11);
  EXPECT_NEAR(pd::critical_stretch(std::nullopt, meet * (1 - 1e-12), c, m2, sy), sy, 1e-11);
  EXPECT_EQ(pd::critical_stretch(0.15, G0, c, m2, sy), 0.15);  // a given stretch wins
}

TEST(BondConstants, DilatationalModulusInEachDimension) {
  const ProbedModuli mod{140e9, 70e9};
  const double E = 9.0 * mod.bulk * mod.shear / (3.0 * mod.bulk + mod.shear);
  const double nu = (3.0 * mod.bulk - 2.0 * mod.shear) / (2.0 * (3.0 * mod.bulk + mod.shear));
  EXPECT_EQ(pd::dilatational_modulus(mod, 3, false), mod.bulk);
  EXPECT_NEAR(pd::dilatational_modulus(mod, 2, false), mod.bulk + mod.shear / 3.0, 1e-6);
  // Plane stress: the in-plane bulk modulus E/(2(1 - nu)).
  EXPECT_NEAR(pd::dilatational_modulus(mod, 2, true), E / (2.0 * (1.0 - nu)), 1e-6 * mod.bulk);
}

TEST(BondConstants, YieldStretchOfTheSoftestSolid) {
  // The gas (material 2) has no bonds and no modulus; the softer solid sets s_y = sigma_y/E_PD.
  const std::vector<double> kd{100e9, 50e9, 0.0};
  const std::vector<std::uint8_t> gas{0, 0, 1};
  EXPECT_DOUBLE_EQ(pd::yield_stretch(750e6, kd, gas, 3), 750e6 / (1.5 * 50e9));
  EXPECT_DOUBLE_EQ(pd::yield_stretch(750e6, kd, gas, 2), 750e6 / (4.0 / 3.0 * 50e9));
}

TEST(BondConstants, PairsInSeriesAndTheGasRules) {
  const std::vector<double> c{1.0, 3.0, 0.0}, s00{0.1, 0.2, kInf};
  const std::vector<std::uint8_t> gas{0, 0, 1};
  const pd::PairConstants k = pd::pair_constants(c, s00, gas);
  ASSERT_EQ(k.c.size(), 9u);
  EXPECT_DOUBLE_EQ(k.c[0 * 3 + 1], 1.5);  // 2 c_a c_b/(c_a + c_b)
  EXPECT_EQ(k.c[1 * 3 + 0], k.c[0 * 3 + 1]);
  EXPECT_DOUBLE_EQ(k.c[1 * 3 + 1], 3.0);
  EXPECT_EQ(k.s00[0 * 3 + 1], 0.1);  // the smaller critical stretch
  EXPECT_EQ(k.c_contact[0 * 3 + 1], k.c[0 * 3 + 1]);
  // A gas end: no bond, no failure; the contact springs are the solid's; gas-gas has none.
  EXPECT_EQ(k.c[0 * 3 + 2], 0.0);
  EXPECT_TRUE(std::isinf(k.s00[2 * 3 + 1]));
  EXPECT_EQ(k.c_contact[2 * 3 + 1], 3.0);
  EXPECT_EQ(k.c_contact[0 * 3 + 2], 1.0);
  EXPECT_EQ(k.c_contact[2 * 3 + 2], 0.0);
}

TEST(BondConstants, SurfaceFactorsOnALatticeCube) {
  // A cube of 7^3 points at unit spacing, horizon 3: the centre has its whole family (factor 1),
  // a face centre about half of it, a corner about an eighth (both counted with their planes).
  const int n = 7;
  std::vector<Vec3> x0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) x0.push_back(Vec3{{double(i), double(j), double(k)}});
  const Index count = static_cast<Index>(x0.size());
  const pd::BondFamily bonds = pd::build_bond_family(x0.data(), count, 3.0, 1.0, 3);
  const std::vector<double> vol0(x0.size(), 1.0);
  const double m1 = pd::lattice_moments(3.0, 1.0, true, 3).m1;
  const std::vector<double> f = pd::surface_factors(bonds, count, vol0.data(), m1);
  auto at = [&](int i, int j, int k) { return f[static_cast<size_t>((i * n + j) * n + k)]; };
  EXPECT_NEAR(at(3, 3, 3), 1.0, 1e-7);  // the family stores its partial volumes as float
  EXPECT_GT(at(3, 3, 0), 1.0);
  EXPECT_LT(at(3, 3, 0), 2.0);
  EXPECT_GT(at(0, 0, 0), at(3, 3, 0));
  EXPECT_LT(at(0, 0, 0), 8.0);
}

}  // namespace test_bond_constants
