// A detonation sliding along a tube (issue 15 item 6: the exploding cylinder lit at one end): the
// peridynamic gas against the continuum. The products behind the front stream axially past the
// case; with the gas family fixed in the reference configuration they lose the case points they
// flow past and push the wall only through the contact springs, so the case is slow (docs/
// validation.md, "The exploding cylinder"). Renewing the gas family in the current configuration
// (peridynamics.gas_refamily_steps) restores the push. The reference is the same charge and case in
// axisymmetric MPM, whose products are a continuum (no family to lose): the case's mass-weighted
// radial velocity over the middle third of the tube at 25 us.
//
// Measured (2026-11-27): MPM 1547 m/s at 0.86 mm and at 0.43 mm (converged). Peridynamics at
// 1.72 mm (2 points through the wall, the example's box): fixed family 1367 m/s (-11.6 %), renewed
// every 5 steps 1467 m/s (-5.1 %); at 0.86 mm (the example) 1313 (-15 %) and 1491 m/s (-3.6 %).
// Bound 8 % at 1.72 mm (the coarse lattice's -5.1 % with room for the fracture pattern, which
// changes with round-off), and the renewal must gain at least 4 % over the fixed family (it gains
// 7.3 %; the fixed family fails the 8 % bound).
#include <gtest/gtest.h>

#include <cstdio>

#include "verification/sliding_detonation_support.hpp"

namespace ballista::test_pd_sliding_detonation {
namespace {

TEST(PdSlidingDetonation, RenewedGasFamilyPushesTheCaseLikeTheContinuum) {
  const double v_ref = sliding::continuum_velocity();

  double v[2];
  for (int renew : {0, 5}) {
    const Scenario sc = parse_deck(sliding::pd_deck(renew), "sliding_pd.yaml");
    auto solver = make_solver(sc);
    const double worst = verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
    v[renew ? 1 : 0] = sliding::middle_third_velocity(solver->points(), 2);
    std::printf("sliding detonation, PD 1.72 mm, gas family %s: middle third %.0f m/s, MPM continuum %.0f m/s "
                "(%+.1f %%), worst residual %.4f of the chemical energy\n",
                renew ? "renewed every 5 steps" : "fixed", v[renew ? 1 : 0], v_ref,
                100.0 * (v[renew ? 1 : 0] / v_ref - 1.0), worst / solver->energies().chemical);
    EXPECT_LT(worst / solver->energies().chemical, 0.02);  // issue 15's bound
  }
  EXPECT_NEAR(v[1] / v_ref, 1.0, 0.08);
  EXPECT_GT(v[1], 1.04 * v[0]);
}

}  // namespace
}  // namespace ballista::test_pd_sliding_detonation
