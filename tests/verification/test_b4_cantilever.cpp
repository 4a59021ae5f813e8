// B4: cantilever first-mode vibration (thesis seed 000 §6.1.1 after Mast et al.; CATALOGUE B4;
// examples/cantilever_beam.yaml). A plane-strain neo-Hookean beam L = 4 m, H = 0.5 m, clamped at
// the fixed grid face x = 0, is released from the Euler-Bernoulli first-mode velocity field
// (`initial_state: cantilever_mode1`). The period from the tip displacement's zero crossings is
// compared with Timoshenko theory (1D finite-element reference, verification_support.hpp) and the
// energy (kinetic + internal) is followed over ~2.25 periods (docs/validation.md, "B4"; H / h = 2
// to 16 and every shape function in slow_b4_cantilever.cpp).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "verification/cantilever_support.hpp"

namespace test_b4_cantilever {

using namespace ballista;
using namespace ballista::verification;

namespace {
// Extra --set overrides of every run: add e.g. "mpm.anti_locking=fbar" to repeat the checks with
// another solver option (the asserted bands hold for the deck as shipped).
const std::vector<std::string> kOverrides = {};
}  // namespace

TEST(B4Cantilever, ReferencePeriods) {
  // The 1D Timoshenko model reduces to Euler-Bernoulli when shear is made rigid and rotary inertia
  // dropped: the Richardson-extrapolated 200/400-element value matches the closed form to 1e-7..4e-7
  // (measured in the Release and the sanitizer builds; the shear penalty's bias is ~2e-7). 1e-5
  // checks the reference model itself, far below the 0.4-11 % period errors the MPM runs are
  // judged by. With shear (kappa = 5/6) and rotary inertia
  // the period is 1.3 % longer at L / H = 8 (shear deformation ~ (H/L)^2 E/(kappa G)).
  const BeamData b = beam_data(load_example("cantilever_beam.yaml"));
  const double T_eb = euler_bernoulli_period(b);
  EXPECT_NEAR(timoshenko_period(b, 5.0 / 6.0, true) / T_eb, 1.0, 1e-5);
  const double T_ti = timoshenko_period(b);
  report("T_euler_bernoulli_s", T_eb);
  report("T_timoshenko_s", T_ti);
  EXPECT_GT(T_ti / T_eb, 1.005);
  EXPECT_LT(T_ti / T_eb, 1.03);
}

TEST(B4Cantilever, GimpFourCellsThroughTheThicknessPeriodAndEnergy) {
  // H / h = 4 (cell 0.125 m, 512 particles, ~7,900 steps).
  const Scenario sc = load_example("cantilever_beam.yaml");
  const BeamData b = beam_data(sc);
  const double T_ti = timoshenko_period(b);
  const CantileverResult r = run_cantilever(b.H / 4, "gimp", kOverrides);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  std::printf("B4 cantilever, GIMP, H/h = 4: T = %.5f s (Timoshenko %.5f s, ratio %.5f), %d crossings, "
              "energy drift %.3e (end %.3e)\n", r.period, T_ti, r.period / T_ti, r.crossings, r.energy_drift, r.energy_end);
  report("T_s", r.period);
  report("T_over_T_timoshenko", r.period / T_ti);
  report("energy_drift_max", r.energy_drift);
  // Four zero crossings (t ~ T/2, T, 3T/2, 2T) in 13.5 s.
  EXPECT_GE(r.crossings, 4);
  // Period: measured 0.9944 T_timoshenko (0.9915 at H/h = 2, 0.9963 at 8: shorter than theory and
  // approaching it under refinement, the stiffening of shear locking, mild with GIMP). The band
  // [0.985, 1.003] keeps the measured value with ~0.9 % of room on the locking side (what H/h = 2
  // gives) and fails a period longer than Timoshenko, which no consistent discretisation of this
  // beam should give at this resolution.
  EXPECT_GT(r.period / T_ti, 0.985);
  EXPECT_LT(r.period / T_ti, 1.003);
  // Energy: USL + FLIP loses energy (no source of energy gain): measured max |E - E0| / E0 =
  // 1.16e-2 over 2.25 periods (4.4e-2 at H/h = 2, 2.1e-3 at 8). 2 % is the measured loss + 70 %.
  EXPECT_LT(r.energy_drift, 0.02);
  EXPECT_LE(r.energy_end, 0.0);
}

TEST(B4Cantilever, Bspline3ClampHolds) {
  // The cubic B-spline at H / h = 4 (512 particles, ~7,900 steps). The fixed face x_min is a
  // bounding face of the boundary-modified basis (Steffen et al., CMES 31 (2008) 107;
  // src/mpm/shape_functions.hpp), which interpolates the face node there, so the zero velocity
  // of the face nodes holds the material at the root.
  const Scenario sc = load_example("cantilever_beam.yaml");
  const BeamData b = beam_data(sc);
  const double T_ti = timoshenko_period(b);
  const CantileverResult r = run_cantilever(b.H / 4, "bspline3", kOverrides);
  ASSERT_TRUE(r.failure.empty()) << r.failure;
  std::printf("B4 cantilever, bspline3, H/h = 4: T = %.5f s (Timoshenko %.5f s, ratio %.5f), %d crossings, "
              "energy drift %.3e (end %.3e)\n", r.period, T_ti, r.period / T_ti, r.crossings, r.energy_drift, r.energy_end);
  report("bspline3_T_over_T_timoshenko", r.period / T_ti);
  report("bspline3_energy_drift_max", r.energy_drift);
  EXPECT_GE(r.crossings, 4);
  // Measured 1.0091 of Timoshenko (H/h = 2, 4, 8: 1.0559, 1.0091, 0.9999: too compliant on coarse
  // grids, converging from above). The old treatment (uniform spline, the face's ghost nodes zeroed)
  // gave 1.0359 here: the root rotated. Band [0.995, 1.02]: the measured value with ~1 % of room,
  // failing the old elastic clamp (3.6 % long) and a locking-side period.
  EXPECT_GT(r.period / T_ti, 0.995);
  EXPECT_LT(r.period / T_ti, 1.02);
  // Energy: measured loss 2.25 % over 2.25 periods (USL + FLIP, as GIMP's 1.16 %); bound 3.5 %.
  EXPECT_LT(r.energy_drift, 0.035);
  EXPECT_LE(r.energy_end, 0.0);
}

}  // namespace test_b4_cantilever
