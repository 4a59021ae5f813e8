// The suite as a whole: every registered model provides the hooks the suite needs, A1 and A2 pass
// the registered models and fail deliberately mis-reduced ones, and verify.json is well formed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "materials/material.hpp"
#include "test_models.hpp"
#include "verify/a1_frame_indifference.hpp"
#include "verify/a2_uniaxial_strain.hpp"
#include "verify/a6_objectivity.hpp"
#include "verify/hook_material.hpp"
#include "verify/verify_json.hpp"
#include "verify/verify_suite.hpp"

namespace test_verify_suite {

using namespace ballista;

// Every registered model must provide `example` (CATALOGUE A6 applies to every model: a new model
// cannot skip the objectivity check), and every hook it has must produce a parameter set the deck
// would accept and the model can be built from.
TEST(VerifyHooks, EveryRegisteredModelHasAValidExample) {
  ASSERT_FALSE(material_registry().empty());
  for (const MaterialFactory& f : material_registry()) {
    SCOPED_TRACE(f.model);
    ASSERT_NE(f.example, nullptr) << "model '" << f.model
                                  << "' has no example_params() hook (needed by ballista verify, A6)";
    EXPECT_NO_THROW((void)make_hook_material(f, f.example(), "example"));
    if (f.reduce_elastic) {
      EXPECT_NO_THROW((void)make_hook_material(f, f.reduce_elastic(1000, 1e4, 1.5e4), "reduce_elastic"));
    }
    if (f.reduce_j2) {
      const ParamValues v = f.reduce_j2(7800, 79e9, 70e9, 285.8e6, 0.0, 0.0);
      EXPECT_FALSE(v.empty()) << "reduce_j2 must support perfect plasticity (CATALOGUE A2)";
      EXPECT_NO_THROW((void)make_hook_material(f, v, "reduce_j2"));
    }
  }
}

// Hook parameters are completed and checked as the deck would: a missing required parameter, an
// out-of-range value and an unknown name are errors that name the model and the hook.
TEST(VerifyHooks, HookParametersAreCheckedLikeTheDeck) {
  const MaterialFactory* f = find_material("j2_plasticity");
  ASSERT_NE(f, nullptr);
  ParamValues v{{"density", 7800}, {"bulk_modulus", 1e9}, {"shear_modulus", 1e9}};
  try {
    (void)complete_hook_params(*f, v, "example");
    ADD_FAILURE() << "missing yield_stress accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("yield_stress"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("j2_plasticity"), std::string::npos) << e.what();
  }
  v["yield_stress"] = -1.0;
  EXPECT_THROW((void)complete_hook_params(*f, v, "example"), Error);
  v["yield_stress"] = 1e8;
  v["no_such_parameter"] = 1.0;
  EXPECT_THROW((void)complete_hook_params(*f, v, "example"), Error);
  v.erase("no_such_parameter");
  const ParamValues full = complete_hook_params(*f, v, "example");
  EXPECT_TRUE(full.count("youngs_modulus"));  // optional, filled with its default (NaN)
}

// A1 and A2 pass the registered models that support them (the numbers the report shows).
TEST(VerifySuite, RegisteredModelsPassA1A2) {
  for (const MaterialFactory& f : material_registry()) {
    SCOPED_TRACE(f.model);
    if (f.reduce_elastic) {
      const VerifyCase c = run_a1(f);
      EXPECT_EQ(c.status, VerifyStatus::Pass) << c.reason;
    }
    if (f.reduce_j2) {
      const VerifyCase c = run_a2(f, A2Hardening::None);
      EXPECT_EQ(c.status, VerifyStatus::Pass) << c.reason;
    }
  }
}

namespace {
// Mis-reduced copies of j2_plasticity: the suite must notice.
ParamValues j2_yield_one_percent_high(double rho, double K, double G, double sy, double hi, double hk) {
  return find_material("j2_plasticity")->reduce_j2(rho, K, G, 1.01 * sy, hi, hk);
}
ParamValues j2_elastic_shear_two_percent_high(double rho, double K, double G) {
  return find_material("j2_plasticity")->reduce_elastic(rho, K, 1.02 * G);
}
ParamValues j2_hardening_forty_percent_low(double rho, double K, double G, double sy, double hi, double hk) {
  return find_material("j2_plasticity")->reduce_j2(rho, K, G, sy, 0.6 * hi, hk);
}
}  // namespace

// A 1 % error in the yield stress moves sigma11 on the plastic legs by 2/3 x 2.9 MPa = 1.9 MPa,
// 2.8e-3 of the peak: far above the A2 tolerance (7.5e-5) and the catalogue's 0.05 MPa. A 2 % error in G changes
// K + 4G/3 by 1.3 %, above A1's 0.5 %. Hardening 40 % low fails the A2-iso comparison.
TEST(VerifySuite, MisreducedModelsFail) {
  MaterialFactory f = *find_material("j2_plasticity");
  f.reduce_j2 = &j2_yield_one_percent_high;
  const VerifyCase a2 = run_a2(f, A2Hardening::None);
  EXPECT_EQ(a2.status, VerifyStatus::Fail);
  EXPECT_GT(a2.max_rel_error, 2e-3);
  f.reduce_elastic = &j2_elastic_shear_two_percent_high;
  A1Problem pb;
  pb.steps = 10000;  // enough to resolve 1.3 %
  const VerifyCase a1 = run_a1(f, pb);
  EXPECT_EQ(a1.status, VerifyStatus::Fail);
  EXPECT_GT(a1.max_rel_error, 0.01);
  f.reduce_j2 = &j2_hardening_forty_percent_low;
  const VerifyCase iso = run_a2(f, A2Hardening::Isotropic);
  EXPECT_EQ(iso.status, VerifyStatus::Fail);
}

namespace {
ParamValues mixed_without_two_thirds(double rho, double K, double G, double sy, double hi, double hk) {
  ParamValues v = test::TestJ2Mixed::reduce_to_j2(rho, K, G, sy, hi, hk);
  v["prager_factor"] = 1.5;
  return v;
}
}  // namespace

// A2 with kinematic hardening (thesis Fig. 4.6c) on a J2 model with Prager hardening: passes all
// three variants (the combined return is exact on this path, like the isotropic one). With the 2/3
// of d alpha = 2/3 H_kin d eps^p dropped, the backstress grows 1.5 times too fast and A2-kin
// fails (measured: stress error 2.1e-2 of the peak, backstress 7.6 % of sigma_y0 off).
TEST(VerifySuite, KinematicHardeningVariant) {
  MaterialFactory f = test::test_factory<test::TestJ2Mixed>();
  for (A2Hardening h : {A2Hardening::None, A2Hardening::Isotropic, A2Hardening::Kinematic}) {
    const VerifyCase c = run_a2(f, h);
    EXPECT_EQ(c.status, VerifyStatus::Pass) << c.test << ": " << c.reason;
    EXPECT_LT(c.max_rel_error, 1e-5) << c.test;
    std::printf("%s: max rel error %.3g;", c.test.c_str(), c.max_rel_error);
    for (const auto& [name, v] : c.scalars)
      if (name == "reverse_radius" || name == "reverse_centre") std::printf(" %s %.5g MPa", name.c_str(), v / 1e6);
    std::printf("\n");
  }
  EXPECT_EQ(run_a6_objectivity(f).status, VerifyStatus::Pass);
  f.reduce_j2 = &mixed_without_two_thirds;
  const VerifyCase bad = run_a2(f, A2Hardening::Kinematic);
  EXPECT_EQ(bad.status, VerifyStatus::Fail);
  EXPECT_GT(bad.max_rel_error, 1e-2);
  std::printf("A2-kin without the 2/3: max rel error %.3g (%s)\n", bad.max_rel_error, bad.reason.c_str());
}

// The suite runs every test of every requested model, concurrently, and records an error of one
// test as that test's failure; unknown names are errors.
TEST(VerifySuite, RunsRequestedTestsAndRejectsUnknownNames) {
  const std::vector<MaterialFactory> reg = material_registry();
  VerifySuiteOptions o;
  o.models = {"linear_elastic"};
  o.tests = {"A2", "A6-objectivity"};
  o.threads = 2;
  const auto cases = run_verify_suite(reg, o);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].test, "A2");
  EXPECT_EQ(cases[0].status, VerifyStatus::NotApplicable);
  EXPECT_EQ(cases[1].status, VerifyStatus::Pass);
  o.models = {"no_such_model"};
  EXPECT_THROW(run_verify_suite(reg, o), Error);
  o.models = {};
  o.tests = {"A9"};
  EXPECT_THROW(run_verify_suite(reg, o), Error);
}

// A check with NaN never passes; a case without checks fails.
TEST(VerifyCase, NaNFailsAndEmptyFails) {
  VerifyCase c;
  EXPECT_FALSE(c.check("nan", std::numeric_limits<double>::quiet_NaN(), 1.0));
  EXPECT_FALSE(c.check("nan at least", std::numeric_limits<double>::quiet_NaN(), 1.0, true));
  c.finish();
  EXPECT_EQ(c.status, VerifyStatus::Fail);
  VerifyCase e;
  e.finish();
  EXPECT_EQ(e.status, VerifyStatus::Fail);
  VerifyCase ok;
  ok.check("fine", 0.5, 1.0);
  ok.finish();
  EXPECT_EQ(ok.status, VerifyStatus::Pass);
}

// JSON text: strings escaped, non-finite numbers null, doubles round-trip.
TEST(VerifyJson, EscapingAndNumbers) {
  EXPECT_EQ(json_quote("a\"b\\c\nd\x01"), "\"a\\\"b\\\\c\\nd\\u0001\"");
  EXPECT_EQ(json_number(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(json_number(std::numeric_limits<double>::infinity()), "null");
  const double x = 0.1 + 0.2;
  EXPECT_EQ(std::stod(json_number(x)), x);
  EXPECT_EQ(std::stod(json_number(-1.2345678901234567e-300)), -1.2345678901234567e-300);
  VerifyCase c;
  c.model = "m";
  c.test = "A1";
  c.series = {{"t", {0.0, 1.0}}};
  c.check("x", 1.0, 2.0);
  c.finish();
  const std::string j = verify_json({c}, {"0.1", 1.5, 2});
  EXPECT_NE(j.find("\"all_passed\": true"), std::string::npos);
  EXPECT_NE(j.find("\"t\": [0,1]"), std::string::npos);
  EXPECT_NE(j.find("\"status\": \"pass\""), std::string::npos);
}

}  // namespace test_verify_suite
