// Gurney's open-faced sandwich under OTM at 0.5 mm cells, against the 10 % (the sandwich,
// the formula and the bounds: test_gurney.cpp). The node re-generations make a run at this size
// sensitive to round-off: the detonation time shifted by 1e-13 s, five draws, gave +3.4 to +8.1 %
// (mean +5.3 %, standard deviation 1.9 %; docs/validation.md), so the mean of three draws is
// asserted, which that spread leaves four deviations inside the bound. ~30 s on 2 threads.
#include <gtest/gtest.h>

#include <cstdio>

#include "materials/explosive_eos.hpp"
#include "verification/gurney_sandwich_support.hpp"

namespace ballista::slow_gurney_otm {
namespace {

using gurney_sandwich::drive;
using gurney_sandwich::PlateResult;

TEST(GurneySandwich, OtmPlateReachesTheGurneyVelocity) {
  const double gurney = gurney_open_sandwich(2440.0, 1.0);
  double mean = 0.0;
  for (const double lit : {0.0, 1e-13, 2e-13}) {
    const PlateResult r = drive(1.0, true, lit, 0.5e-3);
    std::printf("OTM open-faced sandwich, M/C = 1, 0.5 mm, lit at %g s: plate %.0f m/s, Gurney %.0f m/s (%.1f %%), "
                "energy residual %.4f\n",
                lit, r.velocity, gurney, 100.0 * (r.velocity / gurney - 1.0), r.residual);
    mean += r.velocity / 3.0;
    EXPECT_LT(r.residual, 0.05);
  }
  EXPECT_NEAR(mean / gurney, 1.0, 0.10);
}

}  // namespace
}  // namespace ballista::slow_gurney_otm
