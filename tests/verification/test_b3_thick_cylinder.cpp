// B3: thick-walled cylinder under external pressure, plane strain, linear elastic (thesis seed 000
// §6.1.2, Fig. 6.6; CATALOGUE B3; examples/thick_cylinder.yaml). Quarter section with symmetry
// planes; the pressure ramps up over 3 ms and is held while grid damping settles the tube on the
// static Lame solution. The radial displacement of every particle is compared with the
// plane-strain solution u_r = -(1 + nu) P b^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + a^2 / r)
// (the thesis' eq. 6.2 prints (nu - 1) instead of -(1 + nu): see docs/validation.md, B3).
// The Poisson-ratio sweep of thesis Table 6.2 and the third resolution are in
// slow_b3_thick_cylinder_sweep.cpp.
#include <cstdio>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

using namespace ballista;
using namespace ballista::verification;

TEST(B3ThickCylinder, RadialDisplacementMatchesLameSolution) {
  // Two resolutions: the CI resolution (cell_size 0.05, the deck's; ~3.8k particles, ~4 s on 2
  // cores) and one coarser (0.1) to report the observed order.
  const double h[2] = {0.1, 0.05};
  CylinderError e[2];
  std::printf("B3 thick cylinder, nu = 0.3 (K = 56.832 GPa, G = 26.23 GPa), P = 10 MPa:\n");
  std::printf("  %10s %10s %8s %12s %12s %12s %10s\n", "cell_size", "particles", "steps", "rel. L2",
              "RMS [m]", "max rel.", "KE/IE");
  for (int k = 0; k < 2; ++k) {
    e[k] = run_thick_cylinder(load_example("thick_cylinder.yaml", {set_number("grid.cell_size", h[k])}));
    std::printf("  %10.4g %10ld %8ld %12.4e %12.4e %12.4e %10.2e\n", h[k], e[k].particles, e[k].steps,
                e[k].rel_l2, e[k].rms, e[k].max_rel, e[k].ke_over_ie);
    report("rel_L2_h" + std::to_string(k), e[k].rel_l2);
  }
  const double order = observed_order(e[0].rel_l2, e[1].rel_l2);
  report("order_rel_L2", order);
  EXPECT_NEAR(e[1].nu, 0.3, 1e-5);

  // The comparison is with a static solution, so the run must have settled: measured KE/IE
  // 6e-7 and 8e-7 at 6 ms; below 1e-4 the remaining vibration moves particles by ~1 % of u_r at
  // most (its amplitude relative to u_r scales with sqrt(KE/IE)).
  EXPECT_LT(e[0].ke_over_ie, 1e-4);
  EXPECT_LT(e[1].ke_over_ie, 1e-4);
  // Measured 1.56 % (h = 0.1) and 0.90 % (h = 0.05): GIMP with 2x2 particles per cell and no
  // anti-locking at nu = 0.3. The limit 2 % is a regression bound that still separates a sound
  // run from a locked one (locking by K at nu -> 0.5 raises it to ~10 %, see the slow sweep) or
  // from the thesis' misprinted formula (which differs from Lame by (1 - nu)/(1 + nu): 46 %).
  EXPECT_LT(e[1].rel_l2, 0.02);
  // Refinement must reduce the error (order 0.79 measured on this pair, 1.3 on the next one).
  EXPECT_LT(e[1].rel_l2, e[0].rel_l2);
}
