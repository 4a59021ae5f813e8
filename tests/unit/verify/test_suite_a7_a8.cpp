// A7 and A8 on the registered models: the models that reduce to them pass, with first-order
// errors; a model reduced wrongly fails. The wrong reductions are each a real class of bug: a yield
// stress 1 % off (A7), a cap twice as round, a crush curve twice as stiff (A8).
#include <gtest/gtest.h>

#include <cstdio>

#include "verify/a7_misaligned_rate.hpp"
#include "verify/a8_uniaxial_strain_cap.hpp"

namespace test_suite_a7_a8 {

using namespace ballista;

namespace {
std::string describe(const VerifyCase& c) {
  std::string s = c.reason;
  for (const auto& ch : c.checks) s += "\n  " + ch.name + ": " + std::to_string(ch.value) + " vs " + std::to_string(ch.limit);
  return s;
}
ParamValues j2_yield_one_percent_high(double rho, double K, double G, double sy, double hi, double hk) {
  return find_material("j2_plasticity")->reduce_j2(rho, K, G, 1.01 * sy, hi, hk);
}
ParamValues geo_cap_twice_as_round(const GeoReduction& g) {
  GeoReduction h = g;
  h.cap_ratio *= 2.0;
  return find_material("geomodel")->reduce_geo(h);
}
ParamValues geo_crush_twice_as_stiff(const GeoReduction& g) {
  GeoReduction h = g;
  h.p1 *= 0.5;
  return find_material("geomodel")->reduce_geo(h);
}
}  // namespace

TEST(VerifyA7A8, RegisteredModelsPass) {
  int a7 = 0, a8 = 0;
  for (const MaterialFactory& f : material_registry()) {
    SCOPED_TRACE(f.model);
    if (f.reduce_j2) {
      const VerifyCase c = run_a7(f);
      EXPECT_EQ(c.status, VerifyStatus::Pass) << describe(c);
      ++a7;
    }
    if (f.reduce_geo) {
      const VerifyCase c = run_a8(f);
      EXPECT_EQ(c.status, VerifyStatus::Pass) << describe(c);
      ++a8;
    }
  }
  EXPECT_GE(a7, 3);  // j2_plasticity, johnson_cook, geomodel
  EXPECT_GE(a8, 1);  // geomodel
}

// 1 % on the yield stress moves the circle by 1 % of R, 8x A7's tolerance (1.2e-3) and it does not
// shrink with the step.
TEST(VerifyA7A8, YieldOnePercentOffFailsA7) {
  MaterialFactory f = *find_material("j2_plasticity");
  f.reduce_j2 = &j2_yield_one_percent_high;
  const VerifyCase c = run_a7(f);
  EXPECT_EQ(c.status, VerifyStatus::Fail);
  EXPECT_GT(c.max_rel_error, 5e-3);
  std::printf("A7 with the yield stress 1 %% high: max rel error %.3g (tolerance %.3g)\n", c.max_rel_error, c.tolerance);
}

TEST(VerifyA7A8, WrongCapOrCrushCurveFailsA8) {
  MaterialFactory f = *find_material("geomodel");
  f.reduce_geo = &geo_cap_twice_as_round;
  const VerifyCase round = run_a8(f);
  EXPECT_EQ(round.status, VerifyStatus::Fail) << describe(round);
  f.reduce_geo = &geo_crush_twice_as_stiff;
  const VerifyCase stiff = run_a8(f);
  EXPECT_EQ(stiff.status, VerifyStatus::Fail) << describe(stiff);
  std::printf("A8 with CR doubled: %.3g, with P1 halved: %.3g (tolerance %.3g)\n", round.max_rel_error,
              stiff.max_rel_error, stiff.tolerance);
}

}  // namespace test_suite_a7_a8
