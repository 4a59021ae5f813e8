// B6 Taylor bar, slow part (see test_b6_taylor_bar.cpp): the decks at their full resolutions,
// axisymmetric at cell_size 0.2 mm (~10k particles, ~1 min on 2 cores) and the 3D quarter bar at
// 0.4 mm (~33k particles, ~1.5 min). At these sizes the results must fall in the acceptance
// bands and the energy residual under 2 % (axisymmetric) or in its 5 % band (3D) (docs/validation.md, "Taylor bar").
#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

namespace slow_b6_taylor_bar {

using namespace ballista;
using namespace ballista::verification;

TEST(B6TaylorBarSlow, AxisymmetricFullResolution) {
  const Scenario sc = load_example("taylor_bar_mpm.yaml", {"output.interval=0"});
  const TaylorFigures f = run_taylor(sc, "taylor_axisym_h0.2mm");
  expect_in_acceptance_bands(f);
  // Seeding exact in axisymmetry (see the CI test).
  EXPECT_NEAR(f.ke0, ke0_whole_bar(), 1e-12 * ke0_whole_bar());
  // Energy residual after the booked terms (the PIC share of the FLIP/PIC blend and the wall's
  // impulses on its nodes, issue 13), first order in h: measured 0.39 % (2.2 % and 0.88 % at 0.8
  // and 0.4 mm; 0.75 % before the wall's impulses were booked, 1.75 % before the PIC share was).
  // Bound 0.6 %, under issue 13's 2 % for the Taylor bar.
  EXPECT_LT(f.worst_balance, 0.006);
  EXPECT_LT(f.ke_end, 0.01 * f.ke0);
}

TEST(B6TaylorBarSlow, ThreeDimensionalQuarterBarFullResolution) {
  const Scenario sc = load_example("taylor_bar_mpm_3d.yaml", {"output.interval=0"});
  const TaylorFigures f = run_taylor(sc, "taylor_3d_h0.4mm");
  expect_in_acceptance_bands(f);
  // Seeded quarter disk at 0.2 mm spacing: lattice-count error +0.96 % (203 points for
  // pi 16^2 / 4 = 201.1); 2 % bounds it.
  EXPECT_NEAR(f.ke0, 0.25 * ke0_whole_bar(), 0.02 * 0.25 * ke0_whole_bar());
  // Numerical loss measured 4.0 % at 0.4 mm: inside the 5 % acceptance band.
  EXPECT_LT(f.worst_balance, 0.05);
  EXPECT_LT(f.ke_end, 0.01 * f.ke0);
}

}  // namespace slow_b6_taylor_bar
