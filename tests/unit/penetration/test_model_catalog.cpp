// The model table behind `ballista models`: names, parameter checking, defaults, and that an
// evaluation by name returns the library function's value.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "penetration/hydrodynamic.hpp"
#include "penetration/model_catalog.hpp"
#include "penetration/models_cli.hpp"

namespace test_model_catalog {

namespace bp = ballista::penetration;

namespace {
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ballista::Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ModelCatalog, NamesAreUniqueAndEveryParameterHasAUnit) {
  const auto& models = bp::penetration_models();
  EXPECT_EQ(models.size(), 11u);
  for (size_t i = 0; i < models.size(); ++i) {
    EXPECT_FALSE(models[i].equations.empty()) << models[i].name;
    for (size_t j = i + 1; j < models.size(); ++j) EXPECT_NE(models[i].name, models[j].name);
    for (const auto& p : models[i].params) EXPECT_FALSE(p.unit.empty()) << models[i].name << "." << p.key;
  }
}

TEST(ModelCatalog, ParameterErrorsNameTheParameter) {
  const auto& tate = bp::find_penetration_model("tate");
  EXPECT_NE(error_of([&] {
              bp::resolve_model_params(tate, {{"L", 0.1}, {"bogus", 1}});
            }).find("'bogus'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { bp::resolve_model_params(tate, {{"L", 0.1}}); }).find("'rho_p'"), std::string::npos);
  EXPECT_NE(error_of([] { bp::find_penetration_model("tait"); }).find("tate"), std::string::npos);  // lists names
  EXPECT_NE(error_of([] { bp::parse_model_params({"rho_p=1.2.3"}); }).find("rho_p"), std::string::npos);
  EXPECT_NE(error_of([] { bp::parse_model_params({"=3"}); }).find("key=value"), std::string::npos);
  const auto ok = bp::parse_model_params({"R=5e9"});
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_EQ(ok[0].second, 5e9);
}

TEST(ModelCatalog, DefaultsAreFilledAndEvaluationMatchesLibrary) {
  const auto& m = bp::find_penetration_model("eichelberger");
  const auto p =
      bp::resolve_model_params(m, {{"L", 0.1}, {"rho_p", 8960}, {"rho_t", 2300}, {"R", 0}, {"Y", 0}, {"V", 5000}});
  EXPECT_EQ(p.at("lambda"), 1);  // default
  bp::ModelArgs args;
  args.params = p;
  const auto out = m.evaluate(args);
  int found = 0;
  for (const auto& o : out) {
    if (o.key != "P") continue;
    ++found;
    EXPECT_NEAR(o.value, bp::birkhoff_depth(0.1, 8960, 2300), 1e-14);  // R = Y: eq. 3.2
  }
  EXPECT_EQ(found, 1);
}

}  // namespace test_model_catalog
