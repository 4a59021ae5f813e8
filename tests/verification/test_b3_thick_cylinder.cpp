// B3: thick-walled cylinder under external pressure, plane strain, linear elastic (thesis seed 000
// §6.1.2, Fig. 6.6; CATALOGUE B3; examples/thick_cylinder.yaml). Quarter section with symmetry
// planes; the pressure ramps up over 3 ms and is held while grid damping settles the tube on the
// static Lame solution. The radial displacement of every particle is compared with the
// plane-strain solution u_r = -(1 + nu) P b^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + a^2 / r)
// (the thesis' eq. 6.2 prints (nu - 1) instead of -(1 + nu): see docs/validation.md, B3).
// The Poisson-ratio sweep of thesis Table 6.2 and the third resolution are in
// slow_b3_thick_cylinder_sweep.cpp.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

namespace test_b3_thick_cylinder {

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

// F-bar (mpm.anti_locking: fbar, src/mpm/anti_locking.hpp) near incompressibility: first-order
// convergence of the radial displacement at nu = 0.49, an error that does not grow from 0.49 to
// 0.499, and below the unlocked run's at 0.499. Cost: nu = 0.499 needs 12x the steps of nu = 0.3
// (dilatational over shear wave speed) and its h = 0.05 run alone is 79 M particle-steps (~30 s
// of CPU), so the order at 0.499 (1.07 on 0.1 -> 0.05, 1.15 on 0.05 -> 0.025) is asserted in
// slow_b3_thick_cylinder_sweep.cpp (FBarThreeResolutions; other shape functions and MUSL in
// FBarEveryShapeFunction); this test is 48 M particle-steps. Only 0.1 -> 0.05 is in the
// asymptotic range: 0.2 -> 0.1 gives 0.86 at nu = 0.49 (five cells across the wall are too
// coarse), 0.05 -> 0.025 gives 1.18.
TEST(B3ThickCylinder, FBarConvergesNearIncompressibility) {
  struct Row { double nu; const char* al; double h; CylinderError e; };
  Row rows[] = {{0.49, "fbar", 0.1, {}}, {0.49, "fbar", 0.05, {}}, {0.499, "fbar", 0.1, {}}, {0.499, "none", 0.1, {}}};
  std::printf("B3 thick cylinder near incompressibility (by K, G = 26.23 GPa), GIMP, USL:\n");
  std::printf("  %7s %6s %10s %8s %12s %10s\n", "nu", "anti", "cell_size", "steps", "rel. L2", "KE/IE");
  for (Row& r : rows) {
    r.e = run_near_incompressible(r.h, r.nu, r.al);
    std::printf("  %7.3f %6s %10.4g %8ld %12.4e %10.2e\n", r.nu, r.al, r.h, r.e.steps, r.e.rel_l2, r.e.ke_over_ie);
    std::fflush(stdout);
    EXPECT_LT(r.e.ke_over_ie, 1e-4);  // settled (see above)
  }
  const double order = observed_order(rows[0].e.rel_l2, rows[1].e.rel_l2);
  report("fbar_nu0.49_order", order);
  report("fbar_nu0.49_relL2_h0.05", rows[1].e.rel_l2);
  report("fbar_nu0.499_relL2_h0.1", rows[2].e.rel_l2);
  report("none_nu0.499_relL2_h0.1", rows[3].e.rel_l2);
  // Measured order 1.13 (3.99 % -> 1.82 %). The runs are bitwise deterministic on any thread
  // count, so the bound 1 is the requirement itself (issue 13; the thesis' Uintah rates 0.07-0.30
  // are slopes in the particle count, h-orders 0.14-0.6), not a fit to noise.
  EXPECT_GE(order, 1.0);
  // Locking-free: the error does not grow from nu = 0.49 to 0.499 (measured 3.99 % and 3.92 % at
  // h = 0.1; 1.82 % and 1.86 % at 0.05). A 10 % band holds that with margin; a locked scheme moves
  // by a factor (the unlocked runs: 1.80 % and 10.96 %).
  EXPECT_NEAR(rows[2].e.rel_l2 / rows[0].e.rel_l2, 1.0, 0.10);
  // Below the unlocked run at nu = 0.499 (measured 3.92 % vs 10.96 % at h = 0.1): asserted at half.
  // Not at nu = 0.49, nor at 0.499 on fine grids: the unlocked error there is the smaller one
  // (0.49: 1.80 % -> 0.82 %; 0.499 at h = 0.025: 0.78 % vs 0.84 %), because the discretisation is
  // too compliant by a near-uniform fraction of u_r already at nu = 0.3, the excess stiffness of
  // per-particle volume constraints offsets part of it, and the unlocked error, mostly locking,
  // falls at order ~2 here (docs/validation.md, B3).
  EXPECT_LT(rows[2].e.rel_l2, 0.5 * rows[3].e.rel_l2);
  // Regression bound: 2.5 % at h = 0.05 (measured 1.82 %).
  EXPECT_LT(rows[1].e.rel_l2, 0.025);
}

// The cubic B-spline on B3 (nu = 0.3, the deck otherwise unchanged): both grid faces the tube
// touches are symmetry planes, where the solver continues the B-spline across the plane by the
// mirror image of the grid field (docs/deck.md, mpm.shape_function). Relative L2 of u_r at
// h = 0.1 and 0.05, and the mean signed error near the planes and near the 45-degree diagonal.
TEST(B3ThickCylinder, Bspline3AtTheSymmetryPlanes) {
  const double h[2] = {0.1, 0.05};
  CylinderError e[2];
  std::printf("B3 thick cylinder, nu = 0.3, bspline3, USL:\n  %10s %8s %12s %12s %12s %10s\n", "cell_size",
              "steps", "rel. L2", "mean planes", "mean diag.", "KE/IE");
  for (int k = 0; k < 2; ++k) {
    e[k] = run_thick_cylinder(
        load_example("thick_cylinder.yaml", {set_number("grid.cell_size", h[k]), "mpm.shape_function=bspline3"}));
    std::printf("  %10.4g %8ld %12.4e %12.4e %12.4e %10.2e\n", h[k], e[k].steps, e[k].rel_l2, e[k].mean_rel_planes,
                e[k].mean_rel_diagonal, e[k].ke_over_ie);
    std::fflush(stdout);
    report("bspline3_rel_L2_h" + std::to_string(k), e[k].rel_l2);
    report("bspline3_mean_planes_h" + std::to_string(k), e[k].mean_rel_planes);
    report("bspline3_mean_diagonal_h" + std::to_string(k), e[k].mean_rel_diagonal);
    EXPECT_LT(e[k].ke_over_ie, 1e-4);
  }
  report("bspline3_order", observed_order(e[0].rel_l2, e[1].rel_l2));
  // Measured 1.754 % -> 1.157 %; mean error near the planes +1.70 % -> +0.50 %, near the diagonal
  // +1.49 % -> +1.62 % (positive: too compliant). With the old treatment (uniform spline, ghost
  // normals zeroed at the planes) it was 6.05 % -> 3.33 %, planes +4.8 % -> +2.0 %, diagonal
  // +6.5 % -> +4.2 %: the whole quarter was too soft. Bounds: GIMP's CI bound of 2 % at h = 0.05
  // (the old value fails it by 1.7x), a smaller error at the finer grid, and below 1 % near the
  // planes at h = 0.05 (twice the measured value, half the old one).
  EXPECT_LT(e[1].rel_l2, 0.02);
  EXPECT_LT(e[1].rel_l2, e[0].rel_l2);
  EXPECT_LT(std::abs(e[1].mean_rel_planes), 0.01);
}

}  // namespace test_b3_thick_cylinder
