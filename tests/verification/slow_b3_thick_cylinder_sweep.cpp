// B3 thick-walled cylinder, slow part (see test_b3_thick_cylinder.cpp for the problem):
//  1. convergence at nu = 0.3 on three resolutions (cell_size 0.1, 0.05, 0.025);
//  2. the Poisson-ratio sweep of thesis seed 000 Table 6.2, nu = 0.1 ... 0.499, (a) by the bulk
//     modulus at G = 26.23 GPa and (b) by the shear modulus at K = 70.28 GPa, at cell_size 0.1 and
//     0.05, reporting the error and the observed order for each nu (the thesis' Tables 6.3/6.4
//     found orders of only 0.07-0.30 without anti-locking). MPM without an anti-locking scheme is
//     expected to lock as nu -> 0.5, so the sweep asserts only what it measured with margin
//     (docs/validation.md, "B3").
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

using namespace ballista;
using namespace ballista::verification;

namespace {

constexpr double kG0 = kCylinderG0;  // Table 6.2a shear modulus, Pa
constexpr double kK0 = kCylinderK0;  // Table 6.2b bulk modulus, Pa

/// The deck at cell size h with moduli K, G (timing scaled with G: thick_cylinder_deck).
Scenario cylinder(double h, double K, double G) { return thick_cylinder_deck(h, K, G); }

double K_for(double nu, double G) { return bulk_for_nu(nu, G); }
double G_for(double nu, double K) { return shear_for_nu(nu, K); }

const std::vector<double> kNu = {0.1, 0.15, 0.2, 0.25, 0.3, 0.334, 0.35, 0.4, 0.45, 0.495, 0.499};

void sweep(bool by_bulk) {
  std::printf("B3 nu sweep by %s (%s):\n", by_bulk ? "K" : "G",
              by_bulk ? "G = 26.23 GPa" : "K = 70.28 GPa");
  std::printf("  %7s %11s %11s %12s %12s %8s %12s %10s\n", "nu", "K [GPa]", "G [GPa]", "relL2 h=0.1",
              "relL2 h=0.05", "order", "RMS h=0.05", "KE/IE");
  for (double nu : kNu) {
    const double K = by_bulk ? K_for(nu, kG0) : kK0;
    const double G = by_bulk ? kG0 : G_for(nu, kK0);
    const CylinderError c = run_thick_cylinder(cylinder(0.1, K, G));
    const CylinderError f = run_thick_cylinder(cylinder(0.05, K, G));
    const double order = observed_order(c.rel_l2, f.rel_l2);
    std::printf("  %7.4f %11.5g %11.5g %12.4e %12.4e %8.3f %12.4e %10.2e\n", nu, K / 1e9, G / 1e9, c.rel_l2,
                f.rel_l2, order, f.rms, f.ke_over_ie);
    std::fflush(stdout);
    const std::string tag = std::string(by_bulk ? "byK" : "byG") + "_nu" + std::to_string(nu).substr(0, 5);
    report(tag + "_relL2_h0.05", f.rel_l2);
    report(tag + "_order", order);
    EXPECT_NEAR(f.nu, nu, 1e-9);
    // Settled on the static state (see test_b3_thick_cylinder.cpp).
    EXPECT_LT(f.ke_over_ie, 1e-4) << "nu " << nu;
    // Up to nu = 0.45 the CI bound holds on both branches (measured 0.65-1.11 % at h = 0.05).
    if (nu <= 0.45) {
      EXPECT_LT(f.rel_l2, 0.02) << "nu " << nu;
    }
    // Near incompressibility the error grows (locking): measured 3.1 % (by K) and 5.8 % (by G,
    // order 0.24) at nu = 0.499, h = 0.05; 11 % and 6.9 % at h = 0.1. 20 % flags a worsening (or a
    // blow-up) without claiming more than was seen.
    EXPECT_LT(f.rel_l2, 0.20) << "nu " << nu;
  }
}

}  // namespace

TEST(B3ThickCylinderSlow, ConvergenceAtNu03ThreeResolutions) {
  const double h[3] = {0.1, 0.05, 0.025};
  CylinderError e[3];
  std::printf("B3 thick cylinder, nu = 0.3:\n  %10s %10s %8s %12s %12s %8s\n", "cell_size", "particles",
              "steps", "rel. L2", "RMS [m]", "order");
  for (int k = 0; k < 3; ++k) {
    e[k] = run_thick_cylinder(load_example("thick_cylinder.yaml", {set_number("grid.cell_size", h[k])}));
    const double o = k ? observed_order(e[k - 1].rel_l2, e[k].rel_l2) : NAN;
    std::printf("  %10.4g %10ld %8ld %12.4e %12.4e %8.3f\n", h[k], e[k].particles, e[k].steps, e[k].rel_l2,
                e[k].rms, o);
    report("rel_L2_h" + std::to_string(k), e[k].rel_l2);
  }
  EXPECT_LT(e[1].rel_l2, e[0].rel_l2);
  EXPECT_LT(e[2].rel_l2, e[1].rel_l2);
  // Measured 0.79 then 1.32: convergent, unlike the thesis' 0.07-0.30 without anti-locking.
  // Asserting > 0.5 on each pair keeps "convergent at a useful rate" without over-fitting.
  EXPECT_GT(observed_order(e[0].rel_l2, e[1].rel_l2), 0.5);
  EXPECT_GT(observed_order(e[1].rel_l2, e[2].rel_l2), 0.5);
}

TEST(B3ThickCylinderSlow, PoissonSweepByBulkModulus) { sweep(true); }

TEST(B3ThickCylinderSlow, PoissonSweepByShearModulus) { sweep(false); }
