// The exploding cylinder lit at one end with the products on a lattice twice as coarse as the
// case (bodies[].point_spacing, the economy of the example at 8 points through the wall), against
// the continuum: test_pd_sliding_detonation.cpp's check at the example's lattice, 0.86 mm. In the
// slow suite: a 3D run of half a minute, beside the continuum reference.
#include <gtest/gtest.h>

#include <cstdio>

#include "verification/sliding_detonation_support.hpp"

namespace ballista::slow_pd_sliding_detonation {
namespace {

TEST(PdSlidingDetonationSlow, ProductsOnACoarserLatticePushTheCaseLikeTheContinuum) {
  const double v_ref = sliding::continuum_velocity();

  // The products on a lattice twice as coarse as the case (bodies[].point_spacing, the economy of
  // the example at 8 points through the wall): case 0.86 mm, gas 1.72 mm, renewed every 5 steps.
  // Measured 2026-11-27: 1476 m/s (-4.5 %), residual 0.4 %; the example's deck, whose steps also
  // land on its output times, gives 1513 m/s (-2.2 %) against 1491 m/s (-3.6 %) for the uniform
  // 0.86 mm lattice, in 30 s instead of 77 s. The bound of the 1.72 mm check (8 %).
  const Scenario sc = parse_deck(sliding::pd_deck(5, 0.86e-3, 1.72e-3), "sliding_pd_coarse_gas.yaml");
  auto solver = make_solver(sc);
  const double worst = verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
  const double vc = sliding::middle_third_velocity(solver->points(), 2);
  std::printf("sliding detonation, PD case 0.86 mm, gas 1.72 mm, renewed every 5 steps: middle third %.0f m/s "
              "(%+.1f %% against MPM), worst residual %.4f of the chemical energy\n",
              vc, 100.0 * (vc / v_ref - 1.0), worst / solver->energies().chemical);
  EXPECT_NEAR(vc / v_ref, 1.0, 0.08);
  EXPECT_LT(worst / solver->energies().chemical, 0.02);
}

}  // namespace
}  // namespace ballista::slow_pd_sliding_detonation
