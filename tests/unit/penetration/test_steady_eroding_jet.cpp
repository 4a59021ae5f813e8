// Eichelberger and Grove run one steady eroding-jet calculation (strength_models.cpp,
// steady_eroding_jet) with their own effective jet density k: the same k gives the same answer to
// the bit, and each keeps its own message in the rigid regime.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "penetration/strength_models.hpp"

namespace test_steady_eroding_jet {

namespace bp = ballista::penetration;

namespace {

std::string message_of(const auto& call) {
  try {
    call();
  } catch (const ballista::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SteadyErodingJet, GroveWithoutPoresIsEichelbergerToTheBit) {
  // phi = 0: k = rho_d (1 + 0) = rho_d = 1 x rho_p, the same k in the same calculation.
  for (double V : {1500.0, 4000.0, 8000.0}) {
    const auto g = bp::grove({0.2, 8960, 8960, 2300, 1e8, 5e7, V});
    const auto e = bp::eichelberger({0.2, 1, 8960, 2300, 1e8, 5e7, V});
    EXPECT_EQ(g.steady.U, e.U) << "V = " << V;
    EXPECT_EQ(g.steady.P, e.P) << "V = " << V;
    EXPECT_EQ(g.steady.regime, e.regime) << "V = " << V;
  }
}

TEST(SteadyErodingJet, RigidRegimeMessagesNameTheirModel) {
  // rho_t V^2 = 1e9 Pa <= 2 (Y - R) = 1e10 Pa: the jet does not erode.
  EXPECT_EQ(message_of([] { bp::eichelberger({0.3, 1, 8960, 1000, 0, 5e9, 1000}); }),
            "eichelberger: rho_t V^2 = 1e+09 Pa <= 2 (Y - R) = 1e+10 Pa: the jet does not erode (U = V) and eq. 3.8 "
            "does not apply");
  EXPECT_EQ(message_of([] { bp::grove({0.3, 8960, 8960, 1000, 0, 5e9, 1000}); }),
            "grove: rho_t V^2 = 1e+09 Pa <= 2 (Y - R) = 1e+10 Pa: the jet does not erode and eq. 3.13 does not apply");
}

}  // namespace test_steady_eroding_jet
