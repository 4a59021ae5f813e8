// B3: thick-walled cylinder under external pressure, plane strain, linear elastic (thesis seed 000
// §6.1.2, Fig. 6.6; CATALOGUE B3; examples/thick_cylinder.yaml). Quarter section with symmetry
// planes; the pressure ramps up over 3 ms and is held while grid damping settles the tube on the
// static Lame solution. The radial displacement of every particle is compared with the
// plane-strain solution u_r = -(1 + nu) P b^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + a^2 / r)
// (the thesis' eq. 6.2 prints (nu - 1) instead of -(1 + nu): see docs/validation.md, B3).
// The Poisson-ratio sweep of thesis Table 6.2 and the third resolution are in
// slow_b3_thick_cylinder_sweep.cpp.
#include <cstdio>
#include <string>
#include <vector>

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

namespace {

/// The B3 deck near incompressibility: the bulk modulus for nu at the Table 6.2a shear modulus
/// (the sweep "by K" of the slow test; the strains stay ~1e-4, so the small-strain Lame solution
/// is the reference), with the given anti-locking treatment.
CylinderError run_near_incompressible(double h, double nu, const std::string& anti_locking) {
  return run_thick_cylinder(thick_cylinder_deck(h, bulk_for_nu(nu, kCylinderG0), kCylinderG0,
                                                {"mpm.anti_locking=" + anti_locking}));
}

}  // namespace

// F-bar (mpm.anti_locking: fbar, src/mpm/anti_locking.hpp) at nu = 0.499: first-order
// convergence of the radial displacement and an error below the unlocked run's. Cost: nu = 0.499
// needs 12x the steps of nu = 0.3 (dilatational over shear wave speed), ~100 M particle-steps
// here, ~20 s on 2 idle cores; nu = 0.49 and the third resolution are in
// slow_b3_thick_cylinder_sweep.cpp (FBarThreeResolutions), the other shape functions and MUSL in
// FBarEveryShapeFunction. Only 0.1 -> 0.05 is in the asymptotic range: 0.2 -> 0.1 gives 0.60
// (five cells across the wall are too coarse), 0.05 -> 0.025 gives 1.15.
TEST(B3ThickCylinder, FBarConvergesNearIncompressibility) {
  struct Row { const char* al; double h; CylinderError e; };
  Row rows[] = {{"fbar", 0.1, {}}, {"fbar", 0.05, {}}, {"none", 0.1, {}}};
  std::printf("B3 thick cylinder, nu = 0.499 (by K, G = 26.23 GPa), GIMP, USL:\n");
  std::printf("  %6s %10s %8s %12s %10s\n", "anti", "cell_size", "steps", "rel. L2", "KE/IE");
  for (Row& r : rows) {
    r.e = run_near_incompressible(r.h, 0.499, r.al);
    std::printf("  %6s %10.4g %8ld %12.4e %10.2e\n", r.al, r.h, r.e.steps, r.e.rel_l2, r.e.ke_over_ie);
    std::fflush(stdout);
    EXPECT_LT(r.e.ke_over_ie, 1e-4);  // settled (see above)
  }
  const double order = observed_order(rows[0].e.rel_l2, rows[1].e.rel_l2);
  report("fbar_nu0.499_order", order);
  report("fbar_nu0.499_relL2_h0.05", rows[1].e.rel_l2);
  report("none_nu0.499_relL2_h0.1", rows[2].e.rel_l2);
  // Measured order 1.07 (3.92 % -> 1.86 %; the unlocked runs: 10.96 % -> 3.17 %). The runs are
  // bitwise deterministic on any thread count, so the bound 1 is the requirement itself (issue
  // 13: the thesis' Uintah runs reached 0.07-0.30), not a fit to noise. The deck's 6 ms leave
  // F-bar a slow residual creep at this nu: settled (18 ms / 12 ms) the errors are 4.11 % and
  // 1.89 % (order 1.12), so the 6 ms order is the lower one.
  EXPECT_GE(order, 1.0);
  // Below the unlocked run (measured 3.92 % vs 10.96 % at h = 0.1; 1.86 % vs 3.17 % at 0.05 in
  // the slow test): asserted at half. Not asserted at nu = 0.49: there the unlocked runs are barely
  // locked (1.80 % -> 0.82 %, order 1.14) and their error is the smaller one, because the
  // discretisation is too compliant by a near-uniform fraction of u_r already at nu = 0.3, and
  // the excess stiffness of locking partly cancels that; F-bar removes the cancellation
  // (docs/validation.md, B3).
  EXPECT_LT(rows[0].e.rel_l2, 0.5 * rows[2].e.rel_l2);
  // Regression bound: 2.5 % at h = 0.05 (measured 1.86 %).
  EXPECT_LT(rows[1].e.rel_l2, 0.025);
}
