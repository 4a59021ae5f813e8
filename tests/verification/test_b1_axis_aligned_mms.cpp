// B1: axis-aligned displacement manufactured solution (Wallstedt & Guilkey, J. Comput. Phys. 227
// (2008) 9628; CATALOGUE B1; examples/axis_aligned_mms.yaml). A unit cube of compressible
// neo-Hookean material starts on the manufactured solution (displaced by u(X, 0), with its velocity,
// F and stress) and is driven by the manufactured body force; every particle must follow
// x(X, t) = X + u(X, t). The test measures the displacement error at t = 0.02 on three grids and
// asserts second-order-like convergence (docs/validation.md, "B1").
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

namespace test_b1_axis_aligned_mms {

using namespace ballista;
using namespace ballista::verification;

TEST(B1AxisAlignedMms, DisplacementErrorConvergesAtSecondOrder) {
  // Cell sizes 1/4, 1/8, 1/16 (2 particles per cell per direction: 512 ... 32768 particles; about
  // 6 s on 2 cores in total). The deck's full size, 1/32, is added in slow_b1_axis_aligned_mms.cpp.
  const std::vector<double> h = {0.25, 0.125, 0.0625};
  std::vector<MmsError> err;
  std::printf("B1 axis-aligned MMS, t = 0.02, GIMP, USL, FLIP:\n");
  std::printf("  %10s %10s %8s %14s %14s %8s\n", "cell_size", "particles", "steps", "L2 [m]", "Linf [m]", "order");
  for (size_t k = 0; k < h.size(); ++k) {
    err.push_back(run_mms(h[k]));
    const double order = k ? observed_order(err[k - 1].l2, err[k].l2) : NAN;
    std::printf("  %10.5g %10ld %8ld %14.6e %14.6e %8.3f\n", h[k], err[k].particles, err[k].steps,
                err[k].l2, err[k].linf, order);
    report("L2_h" + std::to_string(k), err[k].l2);
    report("Linf_h" + std::to_string(k), err[k].linf);
  }
  const double order_coarse = observed_order(err[0].l2, err[1].l2);
  const double order_fine = observed_order(err[1].l2, err[2].l2);
  const double order_linf = observed_order(err[1].linf, err[2].linf);
  report("order_L2_coarse_pair", order_coarse);
  report("order_L2_fine_pair", order_fine);
  report("order_Linf_fine_pair", order_linf);

  // The error must fall monotonically under refinement.
  EXPECT_LT(err[1].l2, err[0].l2);
  EXPECT_LT(err[2].l2, err[1].l2);
  // Order: GIMP with a smooth solution and pure FLIP converges at second order in space
  // (Wallstedt & Guilkey 2008 report ~2 for GIMP on this problem; the time error, first order in
  // dt but with CFL 0.2 and only ~1 wave period, stays below the spatial error here). Measured
  // 1.73 on the coarse pair (pre-asymptotic: 4 cells per half-wave) and 1.88 on the fine pair.
  // 1.5 sits between first order (a broken stress divergence or boundary treatment) and the
  // measured rate with a margin for round-off-free but resolution-dependent noise.
  EXPECT_GE(order_fine, 1.5);
  // Regression guard on the absolute level: measured 2.69e-3 at h = 1/16 (and matching the lead's
  // independent `ballista run` + h5py measurement 0.00269); 4e-3 allows ~50 % for deliberate
  // changes of the time-step rule before someone has to look.
  EXPECT_LT(err[2].l2, 4.0e-3);
}

TEST(B1AxisAlignedMms, Bspline3AtSymmetryFacesConvergesAtSecondOrder) {
  // The cubic B-spline on the same deck, cell sizes 1/4, 1/8, 1/16 (~8 s on one core). Every face
  // of the cube is a symmetry plane, where the solver continues the spline by the mirror image of
  // the grid field (the manufactured u_x is odd about x = 0 and 1, u_y and u_z even: what the
  // mirror represents). Measured L2 4.585e-2, 1.218e-2, 2.897e-3 (orders 1.91, 2.07; 2.0x on
  // 1/16 -> 1/32 in the slow test). The old treatment (uniform spline, ghost normals zeroed)
  // converged at first order: 7.81e-2, 4.04e-2, 1.90e-2 (0.95, 1.09).
  const std::vector<double> h = {0.25, 0.125, 0.0625};
  std::vector<MmsError> e;
  for (double hk : h) {
    e.push_back(run_mms(hk, {"mpm.shape_function=bspline3"}));
    std::printf("B1 bspline3: h = %g: L2 %.4e, Linf %.4e\n", hk, e.back().l2, e.back().linf);
    report("bspline3_L2_h" + std::to_string(e.size() - 1), e.back().l2);
  }
  const double o1 = observed_order(e[0].l2, e[1].l2), o2 = observed_order(e[1].l2, e[2].l2);
  report("bspline3_order_coarse_pair", o1);
  report("bspline3_order_fine_pair", o2);
  // Bounds: 1.7 and 1.8 (second order with the pre-asymptotic margin GIMP gets on this deck; the
  // old first-order treatment fails both), and GIMP's regression bound 4e-3 at 1/16.
  EXPECT_GE(o1, 1.7);
  EXPECT_GE(o2, 1.8);
  EXPECT_LT(e[2].l2, 4.0e-3);
}

}  // namespace test_b1_axis_aligned_mms
