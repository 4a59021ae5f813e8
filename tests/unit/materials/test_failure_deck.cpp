// failure.* and eos.* in the deck: read from the material's sub-maps (deck_reader.cpp routes dotted
// parameter names), and bad values reported at the right file:line with the key path.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "materials/failure.hpp"

namespace test_failure_deck {

using namespace ballista;

namespace {

// Materials section is `kMaterial`, inserted at line 7 of the deck.
std::string deck(const std::string& material) {
  return "simulation:\n"
         "  end_time: 1.0e-6\n"
         "grid:\n"
         "  lower: [0, 0, 0]\n"
         "  upper: [0.01, 0.01, 0.01]\n"
         "  cell_size: 1.0e-3\n"
         "materials:\n" +
         material +
         "bodies:\n"
         "  - name: block\n"
         "    material: m\n"
         "    shape: {type: box, lower: [0.002, 0.002, 0.002], upper: [0.008, 0.008, 0.008]}\n";
}

const std::string kSteel =
    "  m:\n"
    "    model: linear_elastic\n"
    "    density: 7850\n"
    "    youngs_modulus: 200e9\n"
    "    poisson_ratio: 0.3\n";

int line_of(const std::string& text, const std::string& needle) {
  const size_t pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << needle;
  int line = 1;
  for (size_t i = 0; i < pos && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

DeckError deck_error(const std::string& text) {
  try {
    parse_deck(text, "deck.yaml");
  } catch (const DeckError& e) {
    return e;
  }
  ADD_FAILURE() << "deck accepted:\n" << text;
  return DeckError("", 0, 0, "", "");
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

// A valid failure and eos group reaches the material parameters; absent ones take their defaults.
TEST(FailureDeck, GroupsAreRead) {
  const std::string d = deck(kSteel +
                             "    failure: {criterion: max_stress, erosion: allow_no_shear, max_stress: 1.5e9}\n"
                             "    eos: {type: mie_gruneisen, sound_speed: 4569, hugoniot_slope: 1.49, "
                             "gruneisen_gamma: 2.17}\n");
  const Scenario s = parse_deck(d, "deck.yaml");
  ASSERT_EQ(s.materials.size(), 1u);
  const ParamValues& v = s.materials[0].params;
  EXPECT_EQ(v.choice("failure.criterion"), "max_stress");
  EXPECT_EQ(v.choice("failure.erosion"), "allow_no_shear");
  EXPECT_EQ(v.at("failure.max_stress"), 1.5e9);
  EXPECT_EQ(v.at("failure.reference_strain_rate"), 1.0);
  EXPECT_EQ(v.choice("eos.type"), "mie_gruneisen");
  EXPECT_EQ(v.at("eos.hugoniot_slope"), 1.49);
  // Without the groups: criterion none, eos linear.
  const Scenario plain = parse_deck(deck(kSteel), "deck.yaml");
  EXPECT_EQ(plain.materials[0].params.choice("failure.criterion"), "none");
  EXPECT_EQ(plain.materials[0].params.choice("eos.type"), "linear");
  // resolved.yaml reads back to the same parameters (no -inf or other unreadable default).
  const Scenario again = parse_deck(s.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(again.materials[0].params.choice("failure.erosion"), "allow_no_shear");
  EXPECT_EQ(parse_deck(plain.resolved_yaml, "resolved.yaml").materials[0].params.size(),
            plain.materials[0].params.size());
}

// An unknown failure.criterion names its line, the key path and the choices.
TEST(FailureDeck, UnknownCriterion) {
  const std::string d = deck(kSteel + "    failure:\n      criterion: johnson_cook\n");
  const DeckError e = deck_error(d);
  EXPECT_EQ(e.key_path(), "materials.m.failure.criterion");
  EXPECT_EQ(e.line(), line_of(d, "criterion:"));
  EXPECT_TRUE(contains(e.what(), "deck.yaml:" + std::to_string(line_of(d, "criterion:")) + ":")) << e.what();
  EXPECT_TRUE(contains(e.what(), "johnson_cook_damage")) << e.what();
}

// A missing Johnson-Cook constant is reported by make_failure as a ParamError naming failure.d1;
// the deck reader places it at the failure map (the key itself is absent) with its key path.
TEST(FailureDeck, MissingJohnsonCookConstant) {
  const std::string model =
      "  m:\n"
      "    model: test_scripted_point\n"
      "    failure:\n"
      "      criterion: johnson_cook_damage\n"
      "      d2: 3.44\n"
      "      d3: -2.12\n"
      "      d4: 0.002\n"
      "      d5: 0.61\n";
  const std::string d = deck(model);
  const DeckError e = deck_error(d);
  EXPECT_EQ(e.key_path(), "materials.m.failure.d1");
  EXPECT_EQ(e.line(), line_of(d, "failure:"));  // the failure map's own line
  EXPECT_TRUE(contains(e.what(), "deck.yaml:" + std::to_string(e.line()) + ":")) << e.what();
  EXPECT_TRUE(contains(e.what(), "'materials.m.failure.d1'")) << e.what();
  EXPECT_TRUE(contains(e.what(), "failure.d1 is required when failure.criterion is johnson_cook_damage")) << e.what();
}

// A criterion the model cannot support points at failure.criterion's line.
TEST(FailureDeck, CriterionTheModelCannotSupport) {
  const std::string d = deck(kSteel + "    failure:\n      criterion: johnson_cook_damage\n      d1: 0.05\n");
  const DeckError e = deck_error(d);
  EXPECT_EQ(e.key_path(), "materials.m.failure.criterion");
  EXPECT_EQ(e.line(), line_of(d, "criterion:"));
  EXPECT_TRUE(contains(e.what(), "material 'm' (linear_elastic): failure.criterion johnson_cook_damage needs the "
                                 "equivalent plastic strain"))
      << e.what();
}

// An out-of-range eos.hugoniot_slope is caught by the range of its ParamSpec at its line.
TEST(FailureDeck, OutOfRangeHugoniotSlope) {
  const std::string model =
      "  m:\n"
      "    model: water\n"
      "    eos:\n"
      "      hugoniot_slope: -1.9\n";
  const std::string d = deck(model);
  const DeckError e = deck_error(d);
  EXPECT_EQ(e.key_path(), "materials.m.eos.hugoniot_slope");
  EXPECT_EQ(e.line(), line_of(d, "hugoniot_slope"));
  EXPECT_TRUE(contains(e.what(), "deck.yaml:" + std::to_string(e.line()) + ":")) << e.what();
  EXPECT_TRUE(contains(e.what(), "-1.9")) << e.what();
}

// An unknown key inside the failure map is reported with a suggestion.
TEST(FailureDeck, UnknownKeyInTheFailureMap) {
  const std::string d = deck(kSteel + "    failure: {criterion: max_stress, max_stres: 1e9}\n");
  const DeckError e = deck_error(d);
  EXPECT_EQ(e.key_path(), "materials.m.failure.max_stres");
  EXPECT_TRUE(contains(e.what(), "max_stress")) << e.what();
}

}  // namespace test_failure_deck
