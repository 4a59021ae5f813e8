// The exact and reference solutions behind CATALOGUE A7 and A8 checked against what they must
// satisfy, independently of any material model: A7's closed form against A2's exact uniaxial
// solution and against its own rate equation; A8's reference against the closed form on the flat
// cone, its grid halved, the surface's derivatives by finite differences, and the stationary state.
#include <gtest/gtest.h>

#include <cmath>

#include "verify/j2_deviatoric_legs.hpp"
#include "verify/uniaxial_strain_cap.hpp"
#include "verify/uniaxial_strain_j2.hpp"

namespace test_exact_a7_a8 {

using namespace ballista;

namespace {
const J2PerfectParams kJ2{79e9, 70e9, 165e6};
}

// A uniaxial leg is A2's path: the independent exact solution of uniaxial_strain_j2.hpp must agree
// to round-off (both are closed forms in ln F11).
TEST(J2DeviatoricLegs, UniaxialLegIsA2sExactSolution) {
  const double e_end = 6e-3;
  const J2DeviatoricLegs legs(kJ2, {{e_end, 0.0, 0.0}});
  UniaxialStrainJ2 a2({kJ2.bulk, kJ2.shear, std::sqrt(3.0) * kJ2.tau_y, 0.0, 0.0});
  for (int k = 1; k <= 60; ++k) {
    const double tau = k / 60.0;
    a2.advance_to(tau * e_end);
    const auto s = legs.stress(0, tau);
    EXPECT_NEAR(s[0], a2.sigma11(), 1e-6) << tau;  // Pa, on stresses of 1e8
    EXPECT_NEAR(s[1], a2.sigma22(), 1e-6) << tau;
    EXPECT_NEAR(s[2], a2.sigma22(), 1e-6) << tau;
  }
}

// On the circle the closed form satisfies the Prandtl-Reuss rate ds/dtau = 2G (de - (s.de) s / R^2)
// (central differences, step 1e-5 of the leg: truncation ~1e-10 of 2G|de|), stays on the circle,
// and in the elastic part moves along de; the leg that starts at 150 degrees yields again where the
// straight line meets the circle.
TEST(J2DeviatoricLegs, SatisfiesTheRateEquations) {
  const double a = 60.0 * M_PI / 180.0, b = 210.0 * M_PI / 180.0;
  const std::array<double, 3> leg2 = diagonal_of({5e-3 * std::cos(a), 5e-3 * std::sin(a)}, -1e-3 / 3.0);
  const std::array<double, 3> leg3 = diagonal_of({6e-3 * std::cos(b), 6e-3 * std::sin(b)}, 0.5e-3 / 3.0);
  const J2DeviatoricLegs legs(kJ2, {{4.08e-3, 0.0, 0.0}, leg2, leg3});
  const double R = kJ2.radius(), G2 = 2.0 * kJ2.shear;
  EXPECT_EQ(legs.yield_fraction(1), 0.0);  // 60 degrees: plastic at once
  EXPECT_GT(legs.yield_fraction(2), 0.3);  // 150 degrees: elastic across the interior first
  EXPECT_LT(legs.yield_fraction(2), 0.7);
  for (size_t l = 1; l < 3; ++l) {
    const Dev2 de = deviatoric_components(l == 1 ? leg2 : leg3);
    for (double tau : {0.1, 0.3, 0.6, 0.9}) {
      const double h = 1e-5;
      const Dev2 s = legs.deviator(l, tau), sp = legs.deviator(l, tau + h), sm = legs.deviator(l, tau - h);
      const double ds[2] = {(sp[0] - sm[0]) / (2 * h), (sp[1] - sm[1]) / (2 * h)};
      double expect[2] = {G2 * de[0], G2 * de[1]};
      if (tau > legs.yield_fraction(l)) {
        EXPECT_NEAR(std::hypot(s[0], s[1]), R, 1e-9 * R);
        const double sd = s[0] * de[0] + s[1] * de[1];
        for (int i = 0; i < 2; ++i) expect[i] -= G2 * sd * s[i] / (R * R);
      }
      const double scale = G2 * std::hypot(de[0], de[1]);
      EXPECT_NEAR(ds[0], expect[0], 1e-6 * scale) << l << " " << tau;
      EXPECT_NEAR(ds[1], expect[1], 1e-6 * scale) << l << " " << tau;
    }
  }
  // The mean stress is K times the volumetric strain: 79e9 x (4.08e-3 - 1e-3 + 0.5e-3).
  const auto s = legs.stress(2, 1.0);
  EXPECT_NEAR((s[0] + s[1] + s[2]) / 3.0, 79e9 * 3.58e-3, 1e-3);
}

namespace {
CapSurfaceParams rock(bool fixed) {
  CapSurfaceParams p;
  p.bulk = 10e9;
  p.shear = 7e9;
  p.peak_i1 = 10e6;
  p.fslope = 0.15;
  p.cap_ratio = 1.0;
  p.curve = {-90e6, 1.0 / 300e6, -std::log(0.8)};
  p.fixed_cap = fixed;
  return p;
}
}  // namespace

// g_I and g_X against central differences (step 1 kPa on a MPa-scale surface: truncation ~1e-9),
// on the cone and across the cap; g is continuous at kappa.
TEST(UniaxialStrainCap, SurfaceDerivatives) {
  const CapSurfaceParams p = rock(false);
  const double X = -100e6, h = 1e3;
  const double kappa = (X + p.cap_ratio * p.fslope * p.peak_i1) / (1.0 + p.cap_ratio * p.fslope);
  for (double i1 : {-99e6, -95e6, -90e6, -85e6, kappa - 1e5, -50e6, 0.0}) {
    const CapSurfaceValue v = cap_surface(p, i1, X);
    const double gi = (cap_surface(p, i1 + h, X).g - cap_surface(p, i1 - h, X).g) / (2 * h);
    const double gx = (cap_surface(p, i1, X + h).g - cap_surface(p, i1, X - h).g) / (2 * h);
    EXPECT_NEAR(v.g_i1, gi, 1e-6 * (1.0 + std::abs(gi))) << i1;
    EXPECT_NEAR(v.g_x, gx, 1e-6 * (1.0 + std::abs(gx))) << i1;
  }
  EXPECT_NEAR(cap_surface(p, kappa - 1e-3, X).g, cap_surface(p, kappa + 1e-3, X).g, 1.0);
  EXPECT_NEAR(cap_surface(p, X, X).g, 0.0, 1e-6 * p.fslope * p.peak_i1);  // the cap closes on the hydrostat
}

// On the flat cone the fixed-cap response is linear in e with the slope of the header:
// dI1/de = 3KG (2 sqrt3 g_I - 1) / (G + 9K g_I^2), g_I = -FSLOPE.
TEST(UniaxialStrainCap, FlatConeHasTheClosedFormSlope) {
  const CapSurfaceParams p = rock(true);
  const UniaxialStrainCap ref(p, 0.03);
  const double K = p.bulk, G = p.shear, gi = -p.fslope;
  const double slope = 3 * K * G * (2 * std::sqrt(3.0) * gi - 1) / (G + 9 * K * gi * gi);
  const double e0 = ref.yield_strain(), e1 = e0 + 1e-3;  // I1 from -12.6 to about -47 MPa: still on the cone
  EXPECT_NEAR(ref.i1(e0), -3 * K * e0, 1e-9 * 3 * K * e0);
  EXPECT_NEAR((ref.i1(e1) - ref.i1(e0)) / (e1 - e0), slope, 1e-8 * std::abs(slope));
  // The yield point is on the cone: q = FSLOPE (PEAKI1 - I1).
  EXPECT_NEAR(ref.q(e0), p.fslope * (p.peak_i1 - ref.i1(e0)), 1e-6);
}

// Halving the RK4 grid moves the reference by < 2e-9 of the stress scale (third order where the path
// enters the cap, uniaxial_strain_cap.hpp; measured 1.1e-9),
// the fixed cap settles at the stationary I1*, and there g_I = 1/(2 sqrt3).
TEST(UniaxialStrainCap, ConvergedGridAndStationaryState) {
  for (bool fixed : {true, false}) {
    const UniaxialStrainCap fine(rock(fixed), 0.03, 200000), coarse(rock(fixed), 0.03, 100000);
    double diff = 0.0, scale = 0.0;
    for (int k = 0; k <= 300; ++k) {
      const double e = 0.03 * k / 300.0;
      diff = std::max({diff, std::abs(fine.i1(e) - coarse.i1(e)), std::abs(fine.q(e) - coarse.q(e))});
      scale = std::max(scale, std::abs(fine.i1(e)));
    }
    EXPECT_LT(diff / scale, 2e-9) << fixed;
  }
  const UniaxialStrainCap ref(rock(true), 0.03);
  const double star = ref.stationary_i1();
  EXPECT_NEAR(cap_surface(rock(true), star, -90e6).g_i1, 0.5 / std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(ref.i1(0.03), star, 1e-6 * std::abs(star));
  // The moving cap compacts: the plastic volumetric strain is negative and X moves out.
  const UniaxialStrainCap moving(rock(false), 0.03);
  EXPECT_LT(moving.evp(0.03), -0.01);
  EXPECT_LT(moving.cap(0.03), -120e6);
}

}  // namespace test_exact_a7_a8
