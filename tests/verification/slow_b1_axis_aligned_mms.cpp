// B1 axis-aligned MMS, slow part: the three CI resolutions plus the deck's full size, cell_size
// 1/32 (262,144 particles, ~440 steps, ~1.5 min on 2 cores). See test_b1_axis_aligned_mms.cpp
// for the problem and docs/validation.md ("B1") for the numbers.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

namespace slow_b1_axis_aligned_mms {

using namespace ballista;
using namespace ballista::verification;

TEST(B1AxisAlignedMmsSlow, FourResolutions) {
  const std::vector<double> h = {0.25, 0.125, 0.0625, 0.03125};
  std::vector<MmsError> err;
  std::printf("B1 axis-aligned MMS, t = 0.02, GIMP, USL, FLIP:\n");
  std::printf("  %10s %10s %8s %14s %14s %8s %8s\n", "cell_size", "particles", "steps", "L2 [m]",
              "Linf [m]", "order", "ord.Linf");
  for (size_t k = 0; k < h.size(); ++k) {
    err.push_back(run_mms(h[k]));
    const double o = k ? observed_order(err[k - 1].l2, err[k].l2) : NAN;
    const double oi = k ? observed_order(err[k - 1].linf, err[k].linf) : NAN;
    std::printf("  %10.5g %10ld %8ld %14.6e %14.6e %8.3f %8.3f\n", h[k], err[k].particles, err[k].steps,
                err[k].l2, err[k].linf, o, oi);
    report("L2_h" + std::to_string(k), err[k].l2);
    if (k) report("order_L2_" + std::to_string(k - 1) + "_" + std::to_string(k), o);
  }
  for (size_t k = 1; k < h.size(); ++k) EXPECT_LT(err[k].l2, err[k - 1].l2);
  // The CI criterion (>= 1.5) on the 1/8 -> 1/16 pair (measured 1.88).
  EXPECT_GE(observed_order(err[1].l2, err[2].l2), 1.5);
  // On 1/16 -> 1/32 the observed order drops to 1.54 (L2) and 1.39 (Linf). It is not the time
  // error (at CFL 0.05 instead of 0.2 the errors at 1/8 and 1/16 are ~3 % larger, not smaller);
  // a known candidate is the particle-quadrature error of MPM at a fixed number of particles per
  // cell (Steffen, Kirby & Berzins, IJNME 76 (2008) 922). Asserting 1.3 keeps "clearly better
  // than first order" at the finest level without claiming the asymptotic rate
  // (docs/validation.md, B1).
  EXPECT_GE(observed_order(err[2].l2, err[3].l2), 1.3);
}

TEST(B1AxisAlignedMmsSlow, Bspline3FourResolutions) {
  // The cubic B-spline on the same deck: every face of the cube is a symmetry plane, where the
  // solver continues the B-spline by the mirror image of the grid field (the manufactured u_x is
  // odd about x = 0 and x = 1, u_y, u_z even: exactly what the mirror represents).
  const std::vector<double> h = {0.25, 0.125, 0.0625, 0.03125};
  std::vector<MmsError> err;
  std::printf("B1 axis-aligned MMS, t = 0.02, bspline3, USL, FLIP:\n");
  std::printf("  %10s %10s %8s %14s %14s %8s %8s\n", "cell_size", "particles", "steps", "L2 [m]",
              "Linf [m]", "order", "ord.Linf");
  for (size_t k = 0; k < h.size(); ++k) {
    err.push_back(run_mms(h[k], {"mpm.shape_function=bspline3"}));
    const double o = k ? observed_order(err[k - 1].l2, err[k].l2) : NAN;
    const double oi = k ? observed_order(err[k - 1].linf, err[k].linf) : NAN;
    std::printf("  %10.5g %10ld %8ld %14.6e %14.6e %8.3f %8.3f\n", h[k], err[k].particles, err[k].steps,
                err[k].l2, err[k].linf, o, oi);
    std::fflush(stdout);
    report("bspline3_L2_h" + std::to_string(k), err[k].l2);
    if (k) report("bspline3_order_L2_" + std::to_string(k - 1) + "_" + std::to_string(k), o);
  }
  for (size_t k = 1; k < h.size(); ++k) EXPECT_LT(err[k].l2, err[k - 1].l2);
  // Measured L2 4.585e-2, 1.218e-2, 2.897e-3, 6.852e-4: orders 1.91, 2.07, 2.08 (GIMP: 1.73, 1.88,
  // 1.54). The old treatment (uniform spline, ghost normals zeroed) gave 7.81e-2, 4.04e-2, 1.90e-2,
  // 8.81e-3: first order (0.95, 1.09, 1.11). Asserted: >= 1.8 on both finer pairs.
  EXPECT_GE(observed_order(err[1].l2, err[2].l2), 1.8);
  EXPECT_GE(observed_order(err[2].l2, err[3].l2), 1.8);
}

}  // namespace slow_b1_axis_aligned_mms
