// Gurney's open-faced sandwich under OTM at 0.5 mm cells, against the 10 % (the sandwich,
// the formula and the bounds: test_gurney.cpp). The node re-generations make a run at this size
// sensitive to round-off: the detonation time shifted by 1e-13 s, five draws, gave +3.4 to +8.1 %
// (mean +5.3 %, standard deviation 1.9 %; docs/validation.md), so the mean of three draws is
// asserted, which that spread leaves four deviations inside the bound. ~22 s on 2 threads.
#include <gtest/gtest.h>

#include "materials/explosive_eos.hpp"
#include "verification/gurney_sandwich_support.hpp"

namespace ballista::slow_gurney_otm {
namespace {

TEST(GurneySandwich, OtmPlateReachesTheGurneyVelocity) {
  const double mean = gurney_sandwich::otm_mean_plate_velocity(0.5e-3, 0.05);
  EXPECT_NEAR(mean / gurney_open_sandwich(2440.0, 1.0), 1.0, 0.10);
}

}  // namespace
}  // namespace ballista::slow_gurney_otm
