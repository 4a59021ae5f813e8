// The cohesive limit of a solid (materials/cohesive_limit.hpp): the minimum of the universal
// (Vinet) equation of state in tension, P(x) = 3 K0 (1 - x) / x^2 exp(eta (1 - x)).
#include <gtest/gtest.h>

#include <cmath>

#include "materials/cohesive_limit.hpp"

namespace test_cohesive_limit {

using namespace ballista;

double vinet_pressure(double k0, double k0p, double volume_ratio) {
  const double x = std::cbrt(volume_ratio);
  const double eta = 1.5 * (k0p - 1.0);
  return 3.0 * k0 * (1.0 - x) / (x * x) * std::exp(eta * (1.0 - x));
}

TEST(CohesiveLimit, ClosedFormAtEtaOne) {
  // K0' = 5/3 makes eta = 1: x^2 - 2 = 0, x = sqrt 2, P = 3 K0 (1 - sqrt 2) / 2 exp(1 - sqrt 2).
  const double k0 = 100e9, x = std::sqrt(2.0);
  const double exact = 3.0 * k0 * (1.0 - x) / 2.0 * std::exp(1.0 - x);
  EXPECT_NEAR(vinet_cohesive_volume_ratio(5.0 / 3.0), x * x * x, 1e-13);
  EXPECT_NEAR(vinet_cohesive_limit(k0, 5.0 / 3.0), exact, 1e-12 * k0);
}

TEST(CohesiveLimit, IsTheLowestPressureOfTheCurveInTension) {
  // Brute force over V/V0 in (1, 4] at a step of 1e-5: the sampled minimum is within the
  // curve's change over half a step of the limit (a quadratic minimum: ~1e-10 of K0).
  for (const double k0p : {2.0, 4.0, 4.956, 6.0}) {
    const double k0 = 139e9;
    double lowest = 0.0, at = 0.0;
    for (double v = 1.0; v <= 4.0; v += 1e-5) {
      const double p = vinet_pressure(k0, k0p, v);
      if (p < lowest) lowest = p, at = v;
    }
    EXPECT_NEAR(vinet_cohesive_limit(k0, k0p), lowest, 1e-9 * k0) << "K0' " << k0p;
    EXPECT_NEAR(vinet_cohesive_volume_ratio(k0p), at, 2e-5) << "K0' " << k0p;
    EXPECT_LT(vinet_cohesive_limit(k0, k0p), 0.0);
  }
}

TEST(CohesiveLimit, CopperFromItsUsUpLine) {
  // OFHC copper (data/materials.yaml): rho0 8960, c0 3940, s 1.489; K0 = 139.1 GPa, K0' = 4 s - 1
  // = 4.956. Its limit, about -19.6 GPa at V/V0 = 1.44, is ten times the measured spall strength
  // of copper (1-2 GPa): only a point no solid could hold lies beyond it.
  Eos e;
  e.kind = Eos::Kind::MieGruneisen;
  e.rho0 = 8960.0;
  e.c0 = 3940.0;
  e.s = 1.489;
  const double limit = mie_gruneisen_cohesive_limit(e);
  EXPECT_NEAR(limit, vinet_cohesive_limit(8960.0 * 3940.0 * 3940.0, 4.956), 1e-6);
  EXPECT_NEAR(limit, -19.6e9, 0.1e9);
  EXPECT_NEAR(vinet_cohesive_volume_ratio(4.956), 1.44, 0.01);
}

TEST(CohesiveLimit, NoLimitWithoutAnUsUpLine) {
  Eos linear;
  linear.rho0 = 8960.0;
  linear.bulk = 139e9;
  EXPECT_EQ(mie_gruneisen_cohesive_limit(linear), -INFINITY);
  Eos flat;  // s <= 1/2: K0' <= 1, the binding curve has no minimum
  flat.kind = Eos::Kind::MieGruneisen;
  flat.rho0 = 1000.0;
  flat.c0 = 1500.0;
  flat.s = 0.4;
  EXPECT_EQ(mie_gruneisen_cohesive_limit(flat), -INFINITY);
}

}  // namespace test_cohesive_limit

namespace test_cohesive_limit {

// eos.tension_cap: cohesive_limit sets the cutoff to the limit of the EOS's own line, and refuses
// what it cannot honour (a second cutoff, a linear EOS, a line without a minimum) instead of
// ignoring it.
ParamValues copper_line() {
  ParamValues v{{"eos.sound_speed", 3940.0}, {"eos.hugoniot_slope", 1.489}, {"eos.gruneisen_gamma", 2.02}};
  v.choices["eos.type"] = "mie_gruneisen";
  v.choices["eos.tension_cap"] = "cohesive_limit";
  return v;
}

std::string refusal(const ParamValues& v) {
  try {
    make_eos(v, 139e9, 8960.0);
  } catch (const ParamError& e) {
    return e.param() + ": " + e.what();
  }
  return "accepted";
}

TEST(CohesiveLimit, TensionCapIsTheLimitOfTheMaterialsOwnLine) {
  const Eos e = make_eos(copper_line(), 139e9, 8960.0);
  EXPECT_EQ(e.p_min, mie_gruneisen_cohesive_limit(e));
  EXPECT_NEAR(e.p_min, -19.64e9, 0.01e9);
  ParamValues none = copper_line();
  none.choices["eos.tension_cap"] = "none";
  EXPECT_EQ(make_eos(none, 139e9, 8960.0).p_min, -INFINITY);
}

TEST(CohesiveLimit, TensionCapRefusesWhatItCannotHonour) {
  ParamValues both = copper_line();
  both["eos.min_pressure"] = -1e9;
  EXPECT_NE(refusal(both).find("eos.tension_cap: eos.tension_cap and eos.min_pressure both set"), std::string::npos)
      << refusal(both);
  ParamValues linear;
  linear.choices["eos.type"] = "linear";
  linear.choices["eos.tension_cap"] = "cohesive_limit";
  EXPECT_NE(refusal(linear).find("needs eos.type mie_gruneisen"), std::string::npos) << refusal(linear);
  ParamValues flat = copper_line();
  flat["eos.hugoniot_slope"] = 0.4;
  EXPECT_NE(refusal(flat).find("needs eos.hugoniot_slope > 1/2"), std::string::npos) << refusal(flat);
}

}  // namespace test_cohesive_limit
