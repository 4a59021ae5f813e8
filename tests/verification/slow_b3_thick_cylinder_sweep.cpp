// B3 thick-walled cylinder, slow part (see test_b3_thick_cylinder.cpp for the problem):
//  1. convergence at nu = 0.3 on three resolutions (cell_size 0.1, 0.05, 0.025);
//  2. the Poisson-ratio sweep of thesis seed 000 Table 6.2, nu = 0.1 ... 0.499, (a) by the bulk
//     modulus at G = 26.23 GPa and (b) by the shear modulus at K = 70.28 GPa, at cell_size 0.1 and
//     0.05, reporting the error and the observed order for each nu, without anti-locking (the
//     thesis' Tables 6.3/6.4 found orders of only 0.07-0.30) and with mpm.anti_locking: fbar;
//  3. F-bar against no treatment at nu = 0.49 and 0.499 on three resolutions;
//  4. F-bar at nu = 0.499 with every shape function (USL) and with MUSL.
// Every assertion is what was measured, with the margin stated beside it (docs/validation.md, B3).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

namespace slow_b3_thick_cylinder_sweep {

using namespace ballista;
using namespace ballista::verification;

namespace {

constexpr double kG0 = kCylinderG0;  // Table 6.2a shear modulus, Pa
constexpr double kK0 = kCylinderK0;  // Table 6.2b bulk modulus, Pa

/// The deck at cell size h with moduli K, G (timing and pressure scaled with G:
/// thick_cylinder_deck) and the given mpm.anti_locking.
Scenario cylinder(double h, double K, double G, const std::string& anti_locking = "none") {
  return thick_cylinder_deck(h, K, G, {"mpm.anti_locking=" + anti_locking});
}

double K_for(double nu, double G) { return bulk_for_nu(nu, G); }
double G_for(double nu, double K) { return shear_for_nu(nu, K); }

const std::vector<double> kNu = {0.1, 0.15, 0.2, 0.25, 0.3, 0.334, 0.35, 0.4, 0.45, 0.495, 0.499};

void sweep(bool by_bulk) {
  std::printf("B3 nu sweep by %s (%s); none = no anti-locking, fbar = mpm.anti_locking: fbar:\n",
              by_bulk ? "K" : "G", by_bulk ? "G = 26.23 GPa" : "K = 70.28 GPa");
  std::printf("  %7s %10s %10s %11s %11s %7s %11s %11s %7s %9s\n", "nu", "K [GPa]", "G [GPa]", "none h=0.1",
              "none h=0.05", "order", "fbar h=0.1", "fbar h=0.05", "order", "KE/IE");
  for (double nu : kNu) {
    const double K = by_bulk ? K_for(nu, kG0) : kK0;
    const double G = by_bulk ? kG0 : G_for(nu, kK0);
    const CylinderError c = run_thick_cylinder(cylinder(0.1, K, G));
    const CylinderError f = run_thick_cylinder(cylinder(0.05, K, G));
    const CylinderError cb = run_thick_cylinder(cylinder(0.1, K, G, "fbar"));
    const CylinderError fb = run_thick_cylinder(cylinder(0.05, K, G, "fbar"));
    const double order = observed_order(c.rel_l2, f.rel_l2);
    const double order_fbar = observed_order(cb.rel_l2, fb.rel_l2);
    std::printf("  %7.4f %10.5g %10.5g %11.4e %11.4e %7.3f %11.4e %11.4e %7.3f %9.2e\n", nu, K / 1e9, G / 1e9,
                c.rel_l2, f.rel_l2, order, cb.rel_l2, fb.rel_l2, order_fbar, std::max(f.ke_over_ie, fb.ke_over_ie));
    std::fflush(stdout);
    const std::string tag = std::string(by_bulk ? "byK" : "byG") + "_nu" + std::to_string(nu).substr(0, 5);
    report(tag + "_relL2_h0.05", f.rel_l2);
    report(tag + "_order", order);
    report(tag + "_fbar_relL2_h0.05", fb.rel_l2);
    report(tag + "_fbar_order", order_fbar);
    EXPECT_NEAR(f.nu, nu, 1e-9);
    // Settled on the static state (see test_b3_thick_cylinder.cpp).
    EXPECT_LT(f.ke_over_ie, 1e-4) << "nu " << nu;
    EXPECT_LT(fb.ke_over_ie, 1e-4) << "nu " << nu;
    // Up to nu = 0.45 the CI bound holds on both branches without anti-locking (measured
    // 0.65-1.11 % at h = 0.05 before the pressure of the G branch was scaled; see docs).
    if (nu <= 0.45) {
      EXPECT_LT(f.rel_l2, 0.02) << "nu " << nu;
    }
    // Near incompressibility the unlocked error grows (locking): measured 3.2 % at nu = 0.499,
    // h = 0.05, 11 % at h = 0.1 (both branches once the G branch stays small-strain). 20 % flags a
    // worsening (or a blow-up) without claiming more than was seen.
    EXPECT_LT(f.rel_l2, 0.20) << "nu " << nu;
    // F-bar: measured 1.8-1.9 % at h = 0.05 for nu >= 0.49 on both branches; 2.5 % bound. Its
    // order, >= 1 near incompressibility, is asserted in FBarThreeResolutions.
    EXPECT_LT(fb.rel_l2, 0.025) << "nu " << nu;
  }
}

/// nu, by K (G = 26.23 GPa): the relative L2 errors at the given cell sizes.
std::vector<CylinderError> resolutions(double nu, const std::vector<double>& h, const std::string& anti_locking,
                                       const std::vector<std::string>& more = {}) {
  std::vector<CylinderError> e;
  for (double hk : h) {
    std::vector<std::string> o = {"mpm.anti_locking=" + anti_locking};
    o.insert(o.end(), more.begin(), more.end());
    e.push_back(run_thick_cylinder(thick_cylinder_deck(hk, K_for(nu, kG0), kG0, o)));
  }
  return e;
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

TEST(B3ThickCylinderSlow, FBarThreeResolutions) {
  const std::vector<double> h = {0.1, 0.05, 0.025};
  std::printf("B3 near incompressibility (by K), GIMP, USL: relative L2 of u_r and observed orders\n");
  std::printf("  %7s %6s %11s %11s %11s %7s %7s\n", "nu", "anti", "h=0.1", "h=0.05", "h=0.025", "order1", "order2");
  for (double nu : {0.49, 0.499}) {
    std::vector<CylinderError> e[2];
    const char* names[2] = {"none", "fbar"};
    for (int k = 0; k < 2; ++k) {
      e[k] = resolutions(nu, h, names[k]);
      const double o1 = observed_order(e[k][0].rel_l2, e[k][1].rel_l2);
      const double o2 = observed_order(e[k][1].rel_l2, e[k][2].rel_l2);
      std::printf("  %7.3f %6s %11.4e %11.4e %11.4e %7.3f %7.3f\n", nu, names[k], e[k][0].rel_l2, e[k][1].rel_l2,
                  e[k][2].rel_l2, o1, o2);
      std::fflush(stdout);
      const std::string tag = std::string(names[k]) + "_nu" + std::to_string(nu).substr(0, 5);
      report(tag + "_order_0.1_0.05", o1);
      report(tag + "_order_0.05_0.025", o2);
      report(tag + "_relL2_h0.025", e[k][2].rel_l2);
      for (const CylinderError& x : e[k]) EXPECT_LT(x.ke_over_ie, 1e-4);
    }
    // F-bar converges at first order or better on both pairs (measured 1.13, 1.18 at nu = 0.49 and
    // 1.07, 1.15 at 0.499; the runs are deterministic, the bound 1 is the requirement of issue 13).
    EXPECT_GE(observed_order(e[1][0].rel_l2, e[1][1].rel_l2), 1.0) << "nu " << nu;
    EXPECT_GE(observed_order(e[1][1].rel_l2, e[1][2].rel_l2), 1.0) << "nu " << nu;
    if (nu > 0.495) {
      // At nu = 0.499 F-bar is below the unlocked run on the two coarser grids (measured 3.92 vs
      // 10.96 %, 1.86 vs 3.17 %), not on the finest (0.84 vs 0.78 %): the unlocked error, mostly
      // locking, falls at order ~2 here and meets F-bar's first-order compliance error near
      // h = 0.025 (docs/validation.md, B3). At 0.49 the unlocked error is the smaller throughout.
      for (int k = 0; k < 2; ++k) EXPECT_LT(e[1][k].rel_l2, e[0][k].rel_l2) << "h " << h[k];
    }
  }
}

TEST(B3ThickCylinderSlow, FBarEveryShapeFunction) {
  // nu = 0.499 by K, F-bar, h = 0.1 -> 0.05, with each shape function (USL) and with MUSL (GIMP).
  struct Case { const char* shape; const char* update; };
  const Case cases[] = {{"linear", "usl"}, {"gimp", "usl"}, {"cpdi", "usl"}, {"bspline3", "usl"}, {"gimp", "musl"}};
  std::printf("B3 nu = 0.499 (by K), F-bar:\n  %9s %6s %11s %11s %7s\n", "shape", "update", "h=0.1", "h=0.05", "order");
  for (const Case& c : cases) {
    const auto e = resolutions(0.499, {0.1, 0.05}, "fbar",
                               {std::string("mpm.shape_function=") + c.shape, std::string("mpm.update=") + c.update});
    const double o = observed_order(e[0].rel_l2, e[1].rel_l2);
    std::printf("  %9s %6s %11.4e %11.4e %7.3f\n", c.shape, c.update, e[0].rel_l2, e[1].rel_l2, o);
    std::fflush(stdout);
    report(std::string(c.shape) + "_" + c.update + "_fbar_order", o);
    for (const CylinderError& x : e) EXPECT_LT(x.ke_over_ie, 1e-4);
    if (std::string(c.shape) == "bspline3") {
      // Measured 1.712 % -> 1.136 % (order 0.59), the smallest error of all shape functions at
      // both sizes. Before the symmetry planes continued the spline by the mirror image it was
      // 6.84 % -> 3.66 % (0.90): the old ghost treatment made the whole quarter too compliant
      // (docs/validation.md, B3). The low order is that of this pair, not of F-bar: at nu = 0.3
      // without F-bar the B-spline gives 0.60 on 0.1 -> 0.05 and 1.05 on 0.05 -> 0.025
      // (Bspline3ThreeResolutions). Asserted: convergent (order > 0.45) and < 1.5 % at h = 0.05.
      EXPECT_GT(o, 0.45) << c.shape;
      EXPECT_LT(e[1].rel_l2, 0.015) << c.shape;
    } else {
      // Measured 1.09 (linear), 1.07 (GIMP), 1.08 (CPDI), 1.18 (GIMP, MUSL).
      EXPECT_GE(o, 1.0) << c.shape << " " << c.update;
    }
  }
}

TEST(B3ThickCylinderSlow, Bspline3ThreeResolutions) {
  // The cubic B-spline (USL) at nu = 0.3 on three grids, and at nu = 0.49 (by K) without and with
  // F-bar on two: the symmetry planes x = 0 and y = 0 continue the spline by the mirror image
  // (docs/validation.md, B3).
  std::printf("B3 bspline3, USL: relative L2 of u_r\n  %7s %6s %11s %11s %11s %7s %7s\n", "nu", "anti", "h=0.1",
              "h=0.05", "h=0.025", "order1", "order2");
  const auto e = resolutions(0.3, {0.1, 0.05, 0.025}, "none", {"mpm.shape_function=bspline3"});
  const double o1 = observed_order(e[0].rel_l2, e[1].rel_l2), o2 = observed_order(e[1].rel_l2, e[2].rel_l2);
  std::printf("  %7.3f %6s %11.4e %11.4e %11.4e %7.3f %7.3f\n", 0.3, "none", e[0].rel_l2, e[1].rel_l2, e[2].rel_l2,
              o1, o2);
  std::fflush(stdout);
  report("bspline3_nu0.3_relL2_h0.025", e[2].rel_l2);
  report("bspline3_nu0.3_order_0.05_0.025", o2);
  for (const CylinderError& x : e) EXPECT_LT(x.ke_over_ie, 1e-4);
  EXPECT_LT(e[1].rel_l2, e[0].rel_l2);
  EXPECT_LT(e[2].rel_l2, e[1].rel_l2);
  // Measured 1.755 %, 1.157 %, 0.557 % (orders 0.60, 1.05; GIMP 2.24 %, 1.20 %, 0.62 %). Asserted:
  // order >= 0.9 on the finer pair and < 0.8 % at h = 0.025.
  EXPECT_GE(o2, 0.9);
  EXPECT_LT(e[2].rel_l2, 0.008);
  for (const char* al : {"none", "fbar"}) {
    const auto f = resolutions(0.49, {0.1, 0.05}, al, {"mpm.shape_function=bspline3"});
    const double o = observed_order(f[0].rel_l2, f[1].rel_l2);
    std::printf("  %7.3f %6s %11.4e %11.4e %11s %7.3f\n", 0.49, al, f[0].rel_l2, f[1].rel_l2, "", o);
    std::fflush(stdout);
    report(std::string("bspline3_nu0.49_") + al + "_order", o);
    for (const CylinderError& x : f) EXPECT_LT(x.ke_over_ie, 1e-4);
    // Measured at h = 0.05: 1.080 % (none), 1.396 % (fbar); before the mirrored symmetry planes
    // 2.711 % and 3.911 %. Bound 2 % (GIMP's CI bound at nu = 0.3), and convergent.
    EXPECT_LT(f[1].rel_l2, 0.02) << al;
    EXPECT_LT(f[1].rel_l2, f[0].rel_l2) << al;
  }
}

}  // namespace slow_b3_thick_cylinder_sweep
