// B2: generalized vortex manufactured solution (Kamojjala, Brannon, Sadeghirad & Guilkey,
// Engineering with Computers 31 (2015) 193; Uintah GenVortex.ups; CATALOGUE B2;
// examples/generalized_vortex_mms.yaml). A plane-strain neo-Hookean annulus starts undeformed and
// spinning with the manufactured velocity and is driven by the manufactured body force; every
// particle must follow x = Q(alpha(R, t)) X. Two resolutions per shape function, the displacement
// error at t = 0.1 and its observed order (docs/validation.md, "B2"; three resolutions in
// slow_b2_generalized_vortex_mms.cpp).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

namespace test_b2_generalized_vortex_mms {

using namespace ballista;
using namespace ballista::verification;

namespace {

// Cell sizes 1/16 and 1/32 (8 and 16 cells across the annulus; 3,220 and 12,876 particles, 35 and
// 69 steps): about 1.5 s per shape function on 2 cores.
void check_order(const std::string& sf, double min_order, double max_l2_fine) {
  const double h0 = 0.0625, h1 = 0.03125;
  const MmsError e0 = run_vortex(h0, sf), e1 = run_vortex(h1, sf);
  const double order = observed_order(e0.l2, e1.l2);
  std::printf("B2 generalized vortex, t = 0.1, %s, USL, FLIP:\n", sf.c_str());
  std::printf("  h = %.5g: L2 %.4e Linf %.4e (%ld particles, %ld steps)\n", h0, e0.l2, e0.linf, e0.particles, e0.steps);
  std::printf("  h = %.5g: L2 %.4e Linf %.4e (%ld particles, %ld steps)\n", h1, e1.l2, e1.linf, e1.particles, e1.steps);
  report(sf + "_L2_coarse", e0.l2);
  report(sf + "_L2_fine", e1.l2);
  report(sf + "_order_L2", order);
  EXPECT_LT(e1.l2, e0.l2);
  EXPECT_GE(order, min_order) << sf;
  EXPECT_LT(e1.l2, max_l2_fine) << sf;
}

}  // namespace

// Measured on the 1/16 -> 1/32 pair (L2): linear 1.97, GIMP 1.96, CPDI 1.92, bspline3 1.90; on
// 1/32 -> 1/64 (slow test): 1.68, 2.00, 1.99, 2.01. Second order is what a smooth solution with
// these shape functions allows (Kamojjala et al. 2015 report >= 1.5 for GIMP/CPDI/B-splines);
// asserting 1.7 on the coarse pair leaves ~0.2 of margin for changes of the time-step rule while
// failing on first order (a wrong body force or boundary treatment gives <= 1). The absolute
// levels (regression guard) are the measured 1/32 errors plus ~35 %: linear 2.69e-3,
// GIMP 2.96e-3, CPDI 3.63e-3, bspline3 5.17e-3 (m; displacements are up to 0.4 m).
TEST(B2GeneralizedVortexMms, LinearConvergesAtSecondOrder) { check_order("linear", 1.7, 3.6e-3); }
TEST(B2GeneralizedVortexMms, GimpConvergesAtSecondOrder) { check_order("gimp", 1.7, 4.0e-3); }
TEST(B2GeneralizedVortexMms, CpdiConvergesAtSecondOrder) { check_order("cpdi", 1.7, 4.9e-3); }
TEST(B2GeneralizedVortexMms, Bspline3ConvergesAtSecondOrder) { check_order("bspline3", 1.7, 7.0e-3); }

}  // namespace test_b2_generalized_vortex_mms
