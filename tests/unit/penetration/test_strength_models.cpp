// Strength-corrected jet models (thesis seed 000 eq. 3.5-3.13): limits that reduce to Birkhoff,
// the interface balances they solve, and hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/hydrodynamic.hpp"
#include "penetration/strength_models.hpp"

namespace test_strength_models {

namespace bp = ballista::penetration;

TEST(Eichelberger, ReducesToParticulatedJetWithoutStrengthDifference) {
  // eq. 3.6-3.8 with R - Y = 0 are eq. 3.3-3.4 (thesis text below eq. 3.8). Round-off tolerance.
  for (double lambda : {1.0, 1.5, 2.0}) {
    bp::EichelbergerInput in{0.3, lambda, 8960, 2300, 2e9, 2e9, 6000};
    const auto r = bp::eichelberger(in);
    EXPECT_NEAR(r.U, bp::particulated_jet_velocity(6000, lambda, 8960, 2300), 1e-10);
    EXPECT_NEAR(r.P, bp::particulated_jet_depth(0.3, lambda, 8960, 2300), 1e-13);
  }
}

TEST(Eichelberger, SolvesBalanceAndDepthIsErosionTimeTimesU) {
  bp::EichelbergerInput in{0.3, 1.3, 8960, 7850, 3e9, 1e9, 5000};
  const auto r = bp::eichelberger(in);
  ASSERT_EQ(r.regime, bp::InterfaceRegime::kEroding);
  // eq. 3.6 residual, relative to rho_t U^2 (round-off).
  const double lhs = in.lambda * in.rho_p * (in.V - r.U) * (in.V - r.U), rhs = in.rho_t * r.U * r.U + 2 * (in.R - in.Y);
  EXPECT_NEAR(lhs, rhs, 1e-13 * rhs);
  // eq. 3.8 equals L U/(V - U) (the jet is consumed in L/(V-U)); strength reduces the depth.
  EXPECT_NEAR(r.P, in.L * r.U / (in.V - r.U), 1e-13);
  EXPECT_LT(r.P, bp::particulated_jet_depth(in.L, 1.3, in.rho_p, in.rho_t));
}

TEST(Eichelberger, RegimesOutsideErosion) {
  // 2 (R - Y) >= lambda rho_p V^2: no penetration.
  bp::EichelbergerInput weak{0.3, 1, 8960, 7850, 20e9, 0, 1000};  // 2e10*2 > 8960e6
  const auto r = bp::eichelberger(weak);
  EXPECT_EQ(r.regime, bp::InterfaceRegime::kNoPenetration);
  EXPECT_EQ(r.P, 0);
  // rho_t V^2 <= 2 (Y - R): the jet does not erode, eq. 3.8 does not apply.
  bp::EichelbergerInput rigid{0.3, 1, 8960, 1000, 0, 5e9, 1000};
  EXPECT_THROW(bp::eichelberger(rigid), ballista::Error);
}

TEST(Grove, ReducesToEichelbergerAndBirkhoff) {
  // Pore-free jet (phi = 0): eq. 3.13 is eq. 3.8 with lambda = 1.
  bp::GroveInput g{0.2, 8960, 8960, 2300, 1e8, 5e7, 4000};
  const auto r = bp::grove(g);
  const auto e = bp::eichelberger({0.2, 1, 8960, 2300, 1e8, 5e7, 4000});
  EXPECT_EQ(r.phi, 0);
  EXPECT_NEAR(r.steady.P, e.P, 1e-14);
  // Hydrodynamic porous jet: Birkhoff with lambda = 1 + phi (thesis text below eq. 3.13);
  // rho_d = 6000, rho_s = 8960: phi = 0.330357, P = L sqrt(6000 * 1.330357 / 2300).
  bp::GroveInput h{0.2, 6000, 8960, 2300, 0, 0, 4000};
  const auto rh = bp::grove(h);
  EXPECT_NEAR(rh.phi, 1 - 6000.0 / 8960, 1e-15);
  EXPECT_NEAR(rh.steady.P, 0.2 * std::sqrt(6000 * (1 + rh.phi) / 2300), 1e-14);
  EXPECT_THROW(bp::grove({0.2, 9000, 8960, 2300, 0, 0, 4000}), ballista::Error);  // rho_d > rho_s
}

TEST(PackEvans, HandComputedValues) {
  // alpha = 0: Birkhoff plus the channel radius. L = 0.1 m, rho_p/rho_t = 4: P = 0.2 + 0.005 m.
  bp::PackEvansInput in{0.1, 1, 9200, 2300, 0, 1e9, 2000, 0.005};
  EXPECT_NEAR(bp::pack_evans_depth(in), 0.205, 1e-15);
  // alpha = 2, sigma_y = 1.15e9, V = 1000: x = 2.3e9 / 9.2e9 = 0.25.
  //   inside root (eq. 3.5): 0.1 sqrt(4 * 0.75) + 0.005 = 0.1 * 1.7320508 + 0.005 = 0.17820508
  //   outside root (§6.4):   0.1 * 2 * 0.75 + 0.005 = 0.155
  in.alpha = 2;
  in.sigma_y = 1.15e9;
  in.V = 1000;
  EXPECT_NEAR(bp::pack_evans_penalty(in), 0.25, 1e-15);
  EXPECT_NEAR(bp::pack_evans_depth(in), 0.1 * std::sqrt(3.0) + 0.005, 1e-15);
  in.form = bp::PackEvansForm::kPenaltyOutsideRoot;
  EXPECT_NEAR(bp::pack_evans_depth(in), 0.155, 1e-15);
  in.sigma_y = 5e9;  // x = 1.087 > 1: no real depth
  EXPECT_THROW(bp::pack_evans_depth(in), ballista::Error);
}

TEST(Gladkikh, HandComputedValue) {
  // rho_p = rho_t (gamma = 1), V_tip/V_tail = 4: bracket = (3*4 - 4 sqrt(5)) / 3 = 1.01857603.
  EXPECT_NEAR(bp::gladkikh_depth(0.5, 7850, 7850, 8000, 2000), 0.5 * 1.0185760300002802, 1e-14);
  EXPECT_THROW(bp::gladkikh_depth(0.5, 7850, 7850, 2000, 2000), ballista::Error);  // no gradient
  EXPECT_THROW(bp::gladkikh_depth(0.5, 7850, 7850, 4000, 2000), ballista::Error);  // bracket < 0
}

}  // namespace test_strength_models
