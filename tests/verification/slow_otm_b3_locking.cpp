// OTM at nu = 0.499 (B3, the thick cylinder; by K with G = 26.23 GPa, thesis Table 6.2): does it
// lock, and what does the node-averaged F-bar (otm.anti_locking: fbar) do? Two resolutions,
// h = 0.1 and 0.05 (940 and 3,771 points; ~35,000 steps at h = 0.05; 500 s for the test on 2
// threads). Measured (docs/validation.md, OTM): none 1.47 % -> 0.586 % (order 1.33), fbar 3.29 % ->
// 1.55 % (order 1.09). Asserted: order >= 1 at nu = 0.499 with and without it (a locked run's error
// stalls under refinement), and under 2 % at h = 0.05.
#include <cstdio>

#include <gtest/gtest.h>

#include "verification/otm_cylinder_support.hpp"

namespace slow_otm_b3_locking {

using namespace ballista;
using namespace ballista::verification;

TEST(OtmB3Locking, NearlyIncompressibleConvergesWithAndWithoutFBar) {
  const double K = bulk_for_nu(0.499, kCylinderG0);
  for (const char* locking : {"none", "fbar"}) {
    const CylinderError c = run_thick_cylinder(otm_thick_cylinder(0.1, K, locking));
    const CylinderError f = run_thick_cylinder(otm_thick_cylinder(0.05, K, locking));
    const double order = observed_order(c.rel_l2, f.rel_l2);
    std::printf("OTM B3, nu = 0.499, anti_locking %s: rel. L2 %.4e (h = 0.1), %.4e (h = 0.05), order %.2f\n", locking,
                c.rel_l2, f.rel_l2, order);
    report(std::string("otm_nu0499_") + locking + "_order", order);
    EXPECT_GE(order, 1.0);
    EXPECT_LT(f.rel_l2, 0.02);  // measured 0.59 % and 1.55 %
  }
}

}  // namespace slow_otm_b3_locking
