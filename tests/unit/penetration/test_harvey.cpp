// Harvey stressed-rock correlation (thesis seed 000 eq. 3.14-3.18), field units inside.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/harvey.hpp"

namespace test_harvey {

namespace bp = ballista::penetration;

TEST(Harvey, HandComputedBereaLikeValue) {
  // sigma_ucs = 7000 psi, P_c = 5000 psi, P_p = 2000 psi, porosity 20 %, alpha0 = 1e-4 1/psi,
  // P_ref = 0.5 m. By hand (field units):
  //   a = 0.0967 * 20^0.428 = 0.0967 * 3.604465 = 0.348552           (eq. 3.17)
  //   b = 0.7336 - 1.813e-5 * 7000 = 0.60669                         (eq. 3.18, < 30000 psi)
  //   P_eff = 5000 - 0.348552 * 2000 = 4302.896 psi                  (eq. 3.16, read as P_c - a P_p)
  //   F_BI = 7000 + 0.60669 * 4302.896 = 9610.524 psi                (eq. 3.15)
  //   P = 0.5 exp(1e-4 * (10000 - 9610.524)) = 0.5 * 1.0397159 = 0.519858 m   (eq. 3.14)
  const double psi = bp::kPascalPerPsi;
  const bp::HarveyInput in{0.5, 1e-4 / psi, 7000 * psi, 5000 * psi, 2000 * psi, 0.20};
  const auto r = bp::harvey_depth(in);
  // Tolerances: the last printed digit of each hand value.
  EXPECT_NEAR(r.a, 0.348552, 1e-6);
  EXPECT_NEAR(r.b, 0.60669, 1e-12);
  EXPECT_NEAR(r.P_eff / psi, 4302.896, 1e-3);
  EXPECT_NEAR(r.F_BI / psi, 9610.524, 1e-3);
  EXPECT_NEAR(r.depth, 0.519858, 1e-6);
}

TEST(Harvey, StrongRockBranchAndReference) {
  const double psi = bp::kPascalPerPsi;
  // sigma_ucs = 40000 psi: b = 3.33 exp(-9.55e-5 * 40000) = 3.33 * 0.0219278 = 0.0730196 (eq. 3.18).
  const auto r = bp::harvey_depth({0.5, 1e-4 / psi, 40000 * psi, 5000 * psi, 2000 * psi, 0.20});
  EXPECT_NEAR(r.b, 0.0730196, 1e-7);
  // F_BI = 10000 psi returns P_ref exactly (definition of P_ref below eq. 3.18): unstressed rock.
  const auto ref = bp::harvey_depth({0.5, 1e-4 / psi, 10000 * psi, 0, 0, 0.1});
  EXPECT_NEAR(ref.depth, 0.5, 1e-15);
  EXPECT_THROW(bp::harvey_depth({0.5, 1e-4 / psi, 7000 * psi, 0, 0, 20}), ballista::Error);  // percent, not fraction
}

}  // namespace test_harvey
