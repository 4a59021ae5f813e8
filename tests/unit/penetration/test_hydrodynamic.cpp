// Hydrodynamic penetration (thesis seed 000 eq. 3.1-3.4) against hand-computed values and the
// hydrodynamic column of thesis Table 5.3.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/hydrodynamic.hpp"

namespace test_hydrodynamic {

namespace bp = ballista::penetration;

TEST(Hydrodynamic, LikeDensitiesPenetrateOneLength) {
  // eq. 3.2 with rho_p = rho_t: P = L exactly, and U = V/2.
  EXPECT_DOUBLE_EQ(bp::birkhoff_depth(0.25, 7850, 7850), 0.25);
  EXPECT_DOUBLE_EQ(bp::hydrodynamic_penetration_velocity(3000, 7850, 7850), 1500);
}

TEST(Hydrodynamic, VelocitySatisfiesBernoulliBalance) {
  // eq. 3.1: rho_p (V-U)^2 = rho_t U^2, to round-off (relative 1e-14 of rho_t U^2).
  const double V = 3300, rho_p = 19235, rho_t = 2300;
  const double U = bp::hydrodynamic_penetration_velocity(V, rho_p, rho_t);
  EXPECT_NEAR(rho_p * (V - U) * (V - U), rho_t * U * U, 1e-14 * rho_t * U * U);
  // Depth is U times the erosion time L/(V-U) (text below eq. 3.1) = eq. 3.2.
  EXPECT_NEAR(U * 0.1 / (V - U), bp::birkhoff_depth(0.1, rho_p, rho_t), 1e-15);
}

TEST(Hydrodynamic, ThesisTable53HydrodynamicColumn) {
  // Thesis seed 000 Table 5.3: rods into sandstone, rho_t = 2300 kg/m^3 (§5.2). P_h = L sqrt(rho_p/rho_t):
  //   9.618 g/cm^3, 147.08 mm: sqrt(9618/2300)  = 2.044930 -> 300.768 mm = 30.077 cm (printed 30.08)
  //  14.426 g/cm^3,  98.05 mm: sqrt(14426/2300) = 2.504431 -> 245.559 mm = 24.556 cm (printed 24.56)
  //  19.235 g/cm^3,  73.54 mm: sqrt(19235/2300) = 2.891893 -> 212.670 mm = 21.267 cm (printed 21.27)
  //  24.044 g/cm^3,  58.83 mm: sqrt(24044/2300) = 3.233251 -> 190.212 mm = 19.021 cm (printed 19.02)
  //  38.470 g/cm^3,  36.78 mm: sqrt(38470/2300) = 4.089754 -> 150.421 mm = 15.042 cm (printed 15.04)
  struct Row {
    double rho_gcc, L_mm, P_cm;
  };
  const Row rows[] = {{9.618, 147.08, 30.08},
                      {14.426, 98.05, 24.56},
                      {19.235, 73.54, 21.27},
                      {24.044, 58.83, 19.02},
                      {38.470, 36.78, 15.04}};
  for (const Row& r : rows) {
    const double P = bp::birkhoff_depth(r.L_mm * 1e-3, r.rho_gcc * 1e3, 2300);
    // Tolerance: half a unit of the printed 0.01 cm, plus the printed length's own rounding
    // (0.005 mm times sqrt(rho_p/rho_t) <= 0.0021 cm).
    const double tol_cm = 0.005 + 0.0005 * std::sqrt(r.rho_gcc * 1e3 / 2300);
    EXPECT_NEAR(P * 100, r.P_cm, tol_cm) << "rho_p = " << r.rho_gcc << " g/cm^3";
  }
}

TEST(Hydrodynamic, ParticulatedJetLimits) {
  // eq. 3.4: lambda = 1 is Birkhoff's eq. 3.2; lambda = 2 doubles the effective density.
  EXPECT_DOUBLE_EQ(bp::particulated_jet_depth(0.2, 1, 8960, 2300), bp::birkhoff_depth(0.2, 8960, 2300));
  EXPECT_NEAR(bp::particulated_jet_depth(0.2, 2, 8960, 2300), bp::birkhoff_depth(0.2, 2 * 8960, 2300), 1e-15);
  EXPECT_NEAR(bp::particulated_jet_velocity(5000, 2, 8960, 2300),
              bp::hydrodynamic_penetration_velocity(5000, 2 * 8960, 2300), 1e-11);
}

TEST(Hydrodynamic, RejectsBadInput) {
  EXPECT_THROW(bp::particulated_jet_depth(0.2, 2.5, 8960, 2300), ballista::Error);  // lambda in [1, 2]
  EXPECT_THROW(bp::birkhoff_depth(0.2, -1, 2300), ballista::Error);
  EXPECT_THROW(bp::hydrodynamic_penetration_velocity(-1, 8960, 2300), ballista::Error);
  try {
    bp::birkhoff_depth(0.2, 8960, 0);
    FAIL();
  } catch (const ballista::Error& e) {
    EXPECT_NE(std::string(e.what()).find("rho_t"), std::string::npos) << e.what();
  }
}

}  // namespace test_hydrodynamic
