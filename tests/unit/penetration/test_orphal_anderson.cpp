// Orphal-Anderson fit and its strength difference (thesis seed 000 eq. 5.2-5.5).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "penetration/orphal_anderson.hpp"

namespace test_orphal_anderson {

namespace bp = ballista::penetration;

TEST(OrphalAnderson, FitRecoversExactLine) {
  // Synthetic exact data U = a + b V: the fit returns a, b to round-off and r^2 = 1.
  const double a = -120, b = 0.672;
  std::vector<double> V, U;
  for (double v = 1500; v <= 3900; v += 300) {
    V.push_back(v);
    U.push_back(a + b * v);
  }
  const auto f = bp::fit_orphal_anderson(V, U);
  EXPECT_NEAR(f.a, a, 1e-9);
  EXPECT_NEAR(f.b, b, 1e-13);
  EXPECT_NEAR(f.r2, 1, 1e-14);
}

TEST(OrphalAnderson, FitOfScatteredDataHasHandComputedCoefficients) {
  // V = 1, 2, 3 km/s, U = 0.6, 1.4, 1.9 km/s: mean V 2000, mean U 1300; Svv = 2e6, Svu = 1.3e6,
  // Suu = (0.49 + 0.01 + 0.36) e6 = 0.86e6: b = 0.65, a = 1300 - 1300 = 0, r^2 = 1.69/1.72.
  const auto f = bp::fit_orphal_anderson({1000, 2000, 3000}, {600, 1400, 1900});
  EXPECT_NEAR(f.b, 0.65, 1e-14);
  EXPECT_NEAR(f.a, 0, 1e-10);
  EXPECT_NEAR(f.r2, 1.69 / 1.72, 1e-14);
  EXPECT_THROW(bp::fit_orphal_anderson({1000, 1000}, {600, 700}), ballista::Error);
  EXPECT_THROW(bp::fit_orphal_anderson({1000}, {600}), ballista::Error);
}

TEST(OrphalAnderson, StrengthDifferenceMatchesPrintedEquation53) {
  // Eq. 5.3 as printed, with its middle term read as 2 a b V:
  // (a^2 + 2abV + b^2V^2)(rho_p - rho_t)/2 - a rho_p V - (b - 1/2) rho_p V^2.
  const double rp = 19235, rt = 2300;
  for (double a : {-300.0, 0.0, 250.0})
    for (double b : {0.3, 0.634, 0.8})
      for (double V : {1500.0, 3300.0}) {
        const double printed =
            (a * a + 2 * a * b * V + b * b * V * V) * (rp - rt) / 2 - a * rp * V - (b - 0.5) * rp * V * V;
        EXPECT_NEAR(bp::orphal_anderson_strength_difference(a, b, rp, rt, V), printed, 1e-12 * rp * V * V);
      }
  // Hydrodynamic law (a = 0, b = hydrodynamic slope): R - Y = 0 at every V.
  const double bh = bp::orphal_anderson_hydrodynamic_slope(rp, rt);
  EXPECT_NEAR(bp::orphal_anderson_strength_difference(0, bh, rp, rt, 3000), 0, 1e-9 * rp * 9e6);
}

TEST(OrphalAnderson, ExtremumIsWhereDerivativeVanishes) {
  // V_m of eq. 5.4 is a zero of d(R - Y)/dV (central difference, h = 1 m/s: R - Y is quadratic,
  // so the central difference is exact up to round-off ~ 1e-16 * 1e13 / 1 = 1e-3 Pa/(m/s)).
  const double rp = 19235, rt = 2300;
  for (double b : {0.5, 0.9}) {
    const double a = 400;
    const double Vm = bp::orphal_anderson_extremum_velocity(a, b, rp, rt);
    auto f = [&](double V) { return bp::orphal_anderson_strength_difference(a, b, rp, rt, V); };
    const double h = 1, d1 = (f(Vm + h) - f(Vm - h)) / (2 * h), d2 = (f(Vm + h) - 2 * f(Vm) + f(Vm - h)) / (h * h);
    EXPECT_NEAR(d1, 0, 1e-2) << "b = " << b;
    EXPECT_NEAR(d2, bp::orphal_anderson_curvature(b, rp, rt), 1e-3 * rp) << "b = " << b;  // eq. 5.5
  }
}

TEST(OrphalAnderson, HydrodynamicSlopesOfThesisFigure510) {
  // Thesis §5.2: eq. 5.5 changes sign at b = 0.743 (tungsten) and 0.664 (copper) into sandstone
  // (rho_t = 2300). Tungsten 19235 kg/m^3 (Table 5.3); copper 8960 kg/m^3 (handbook value, not
  // given in the seed). b = 1/(1 + sqrt(rho_t/rho_p)) = 0.74306 and 0.66372; printed to 3 decimals.
  EXPECT_NEAR(bp::orphal_anderson_hydrodynamic_slope(19235, 2300), 0.743, 5e-4);
  EXPECT_NEAR(bp::orphal_anderson_hydrodynamic_slope(8960, 2300), 0.664, 5e-4);
  EXPECT_NEAR(bp::orphal_anderson_curvature(bp::orphal_anderson_hydrodynamic_slope(19235, 2300), 19235, 2300), 0,
              1e-10);
  // The simulated tungsten slopes 0.634 and 0.672 lie below 0.743: a minimum (eq. 5.5 > 0), as the thesis says.
  EXPECT_GT(bp::orphal_anderson_curvature(0.634, 19235, 2300), 0);
  EXPECT_GT(bp::orphal_anderson_curvature(0.672, 19235, 2300), 0);
}

}  // namespace test_orphal_anderson
