// Verification of the linear peridynamic solid (formulation: lps; src/peridynamics/lps_pass.hpp) at
// a Poisson's ratio a bond-based solid cannot have (nu = 0.3): the longitudinal wave speed of a thin
// bar, and the energy released per unit area of new crack in a slow separation. Write-up:
// docs/validation.md ("Peridynamics: the state-based solid"). The lattice references are sums over
// the family of an interior point (pd_support.hpp's lattice and the sums below), not the solver.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/lps_lattice.hpp"
#include "verification/pd_support.hpp"
#include "verification/verification_support.hpp"

namespace test_pd_lps {

using namespace ballista;
using namespace ballista::verification;

namespace {

constexpr double kNuLps = 0.3;

}  // namespace

// The thin bar of the bond-based test (4 x 4 x 96 mm, Gaussian pulse, energy-centroid arrivals), in
// a material of E = 72 GPa and nu = 0.3. Reference: the thin-bar speed of the LPS lattice,
// sqrt(E_100 / rho) times the Rayleigh-Love factor at nu = 0.3. The LPS lattice at m = 3 (partial
// volumes) is a cubic solid with the bulk modulus K exactly and (C11 - C12)/2 = Q' mu
// (support/lps_lattice.hpp), so along [100] E_100 = (C11 - C12)(C11 + 2 C12)/(C11 + C12) =
// 9 K Q' mu / (3 K + Q' mu) = 0.890 E. A bond-based solid of this material would take only its
// bulk modulus, E = 3K/2 = 90 GPa in the continuum (a bar 12 % too fast).
// Measured: +19.1 % and +9.2 % against c_m at dx = 1 and 0.5 mm, observed order 1.06, extrapolated
// -0.75 %. The error is again the bar's surface layer, first order in dx at fixed m, but of the
// other sign than the bond-based bar's: a point near a face has a smaller weighted volume m_p, and
// the deviatoric stiffness 15 mu / m_p of its bonds grows as m_p falls. The bounds are the
// bond-based test's: the order within 0.7-1.5, the extrapolated speed within 2 % of c_m (the
// unresolved second-order dispersion term) and within 10 % of c0 (the lattice's floor,
// sqrt(E_100/E) - 1 = -5.7 %, plus margin).
TEST(PdLpsVerification, ThinBarWaveSpeedAtPoissonRatioPointThree) {
  const double K = pdv::kE / (3 * (1 - 2 * kNuLps)), mu = pdv::kE / (2 * (1 + kNuLps));
  const double qp = test::lps_lattice_sums().qprime;
  const double e100 = 9 * K * qp * mu / (3 * K + qp * mu);
  const pdv::BarGeometry g;
  const double c0 = std::sqrt(pdv::kE / pdv::kRho);
  const double cm = std::sqrt(e100 / pdv::kRho) * pdv::love_factor(g, kNuLps);
  std::printf("nu = 0.3: c0 = %.1f m/s; LPS lattice bar speed c_m = %.1f m/s (E_100 / E = %.4f, Q' = %.4f)\n", c0,
              cm, e100 / pdv::kE, qp);
  const pdv::WaveStudy st = pdv::wave_study(g, cm, c0, "pd_lps_wave", "formulation: lps", kNuLps);
  const double e0 = st.error_coarse, e1 = st.error_fine, p = st.order, c_ext = st.extrapolated;
  EXPECT_LT(e1, e0);
  EXPECT_GT(p, 0.7);
  EXPECT_LT(p, 1.5);
  EXPECT_NEAR(c_ext / cm, 1.0, 0.02);
  EXPECT_LT(std::abs(c_ext / c0 - 1), 0.10);
}

// Slow separation of the pre-cracked 24 mm cube (pd_support.hpp: the halves opened as rigid bodies
// through every critical opening of the lattice), LPS with the lattice calibration, G0 = 8 J/m^2:
// the dissipated energy per unit area of the ligament against G0. The critical stretch
// (lps_constants.hpp) takes each crossing bond's deviatoric energy at zero dilatation; it leaves out
// the dilatation of the points beside the opening crack and the coupling of the bonds through it.
// Measured 0.985 G0. Bound 5 %: three times that, and tight enough to reject the bond-based
// constants' error on this lattice (13 %, test_pd_wave_and_fracture.cpp).
TEST(PdLpsVerification, SlowSeparationReleasesTheFractureEnergy) {
  const double g0 = 8.0;
  const pdv::FractureResult r =
      pdv::measure_fracture(1e-3, 24e-3, 12e-3, g0, true, 0.0, 0.0, "lattice", "formulation: lps");
  std::printf("LPS slow separation: %ld of %ld crossing bonds broken, %ld off the plane; G_measured / G0 = %.4f\n",
              r.broken_crossing, r.crossing, r.broken_off, r.g_measured / g0);
  report("pd_lps_release_slow_G_over_G0", r.g_measured / g0);
  EXPECT_EQ(r.broken_crossing, r.crossing);
  EXPECT_EQ(r.broken_off, 0);  // rigid halves: no other bond is stretched
  EXPECT_NEAR(r.g_measured / g0, 1.0, 0.05);
}

}  // namespace test_pd_lps
