// Deck overrides that append to a list (`--set key.path+=value`): items, creation, order with
// "=", errors, and the attribution of validation errors in appended items (docs/deck.md).
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "deck/deck_overrides.hpp"
#include "deck/deck_reader.hpp"
#include "support/deck_errors.hpp"

namespace test_override_append {

using namespace ballista;
using ballista::test::parse_error;

namespace {

const std::string kDeck = R"(simulation:
  end_time: 8.0e-5
  dimension: 3d
grid:
  lower: [-0.01, 0, -0.01]
  upper: [0.01, 0.04, 0.01]
  cell_size: 0.5e-3
materials:
  copper: {model: linear_elastic, density: 8930, youngs_modulus: 117e9, poisson_ratio: 0.35}
bodies:
  - name: bar
    material: copper
    shape: {type: cylinder, center: [0, 0.001, 0], axis: y, radius: 3.2e-3, length: 32.4e-3}
    velocity: [0, -227, 0]
loads:
  - {type: pressure, body: bar, surface: top, pressure: 1e6, curve: [[0, 0], [1e-5, 1]]}
probes:
  - {name: final_length, type: extent, body: bar, axis: y}
  - {name: max_eqps, type: field_max, body: bar, field: eqps}
output:
  interval: 1e-5
)";

const std::string kTipSpeed = "{name: tip_speed, type: mean_velocity, body: bar, axis: y}";
const std::string kKinetic = "{name: ke, type: energy, field: kinetic}";

/// kDeck without its probes section.
std::string deck_without_probes() {
  const size_t b = kDeck.find("probes:");
  return kDeck.substr(0, b) + kDeck.substr(kDeck.find("output:"));
}

/// 1-based line of the first occurrence of `needle` in `text` (0 if absent).
int line_of(const std::string& text, const std::string& needle) {
  const size_t pos = text.find(needle);
  if (pos == std::string::npos) return 0;
  int line = 1;
  for (size_t i = 0; i < pos; ++i)
    if (text[i] == '\n') ++line;
  return line;
}

std::vector<std::string> probe_names(const Scenario& s) {
  std::vector<std::string> names;
  for (const auto& p : s.probes) names.push_back(p.name);
  return names;
}


bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(DeckOverrideAppend, ParseRecognisesPlusEquals) {
  const DeckOverride a = parse_override("probes += [a, b]", "deck.yaml");
  EXPECT_TRUE(a.append);
  EXPECT_EQ(a.key_path, "probes");
  EXPECT_TRUE(a.value.IsSequence());
  // A '+' in the value is not an append.
  const DeckOverride s = parse_override("simulation.end_time=+1e+5", "deck.yaml");
  EXPECT_FALSE(s.append);
  EXPECT_EQ(s.key_path, "simulation.end_time");
  EXPECT_EQ(s.value.Scalar(), "+1e+5");
}

TEST(DeckOverrideAppend, AppendOneMapItemToProbes) {
  const Scenario s = parse_deck(kDeck, "deck.yaml", {"probes+=" + kTipSpeed});
  EXPECT_EQ(probe_names(s), (std::vector<std::string>{"final_length", "max_eqps", "tip_speed"}));
  EXPECT_EQ(s.probes[2].type, "mean_velocity");
  EXPECT_EQ(s.probes[2].params.choice("body"), "bar");
  EXPECT_TRUE(contains(s.resolved_yaml, "tip_speed")) << s.resolved_yaml;
  // The deck's own probes keep their positions in the file; the appended one has none (line 0),
  // as a value set with "=".
  EXPECT_EQ(s.probes[0].mark.line, line_of(kDeck, "final_length"));
  EXPECT_EQ(s.probes[1].mark.line, line_of(kDeck, "max_eqps"));
  EXPECT_EQ(s.probes[2].mark.line, 0);
}

TEST(DeckOverrideAppend, AppendSequenceOfItems) {
  const Scenario s = parse_deck(kDeck, "deck.yaml", {"probes+=[" + kTipSpeed + ", " + kKinetic + "]"});
  EXPECT_EQ(probe_names(s), (std::vector<std::string>{"final_length", "max_eqps", "tip_speed", "ke"}));

  // A list of rows is appended row by row: [[t, v]] adds one point to the curve of loads.0
  // (an index inside the path, as for "=").
  const Scenario c = parse_deck(kDeck, "deck.yaml", {"loads.0.curve+=[[2e-5, 0.5]]"});
  ASSERT_EQ(c.loads[0].curve.t.size(), 3u);
  EXPECT_EQ(c.loads[0].curve.t[2], 2e-5);
  EXPECT_EQ(c.loads[0].curve.v[2], 0.5);

  // An empty list appends nothing.
  const Scenario e = parse_deck(kDeck, "deck.yaml", {"probes+=[]"});
  EXPECT_EQ(e.probes.size(), 2u);
}

TEST(DeckOverrideAppend, SeveralAppendsApplyInOrder) {
  const Scenario s = parse_deck(kDeck, "deck.yaml", {"probes+=" + kKinetic, "probes+=" + kTipSpeed});
  EXPECT_EQ(probe_names(s), (std::vector<std::string>{"final_length", "max_eqps", "ke", "tip_speed"}));
  // An appended item is a list element like any other for a later "=".
  const Scenario r = parse_deck(kDeck, "deck.yaml", {"probes+=" + kKinetic, "probes.2.name=kinetic"});
  EXPECT_EQ(r.probes[2].name, "kinetic");
}

TEST(DeckOverrideAppend, AppendCreatesMissingList) {
  const std::string d = deck_without_probes();
  const Scenario s = parse_deck(d, "deck.yaml", {"probes+=" + kTipSpeed});
  EXPECT_EQ(probe_names(s), (std::vector<std::string>{"tip_speed"}));
  EXPECT_EQ(s.probes[0].mark.line, 0);
  // An empty key counts as absent; a single value (not a list) becomes the list's one item.
  const Scenario f = parse_deck(kDeck + "  fields:\n", "deck.yaml", {"output.fields+=eqps", "output.fields+=[stress]"});
  EXPECT_EQ(f.output.fields, (std::vector<std::string>{"eqps", "stress"}));
  // Missing intermediate maps are created as for "=" (here the output section).
  const std::string no_output = kDeck.substr(0, kDeck.find("output:"));
  const Scenario m = parse_deck(no_output, "deck.yaml", {"output.fields+=[eqps]"});
  EXPECT_EQ(m.output.fields, (std::vector<std::string>{"eqps"}));
}

TEST(DeckOverrideAppend, AppendInsideAJetBodyPath) {
  const std::string jet = R"(simulation: {dimension: axisymmetric, end_time: 1.0e-5}
grid: {lower: [0, 0, 0], upper: [0.02, 0.2, 0], cell_size: 1.0e-3}
materials:
  cu: {model: linear_elastic, density: 8930, youngs_modulus: 117e9, poisson_ratio: 0.35}
  rock: {model: linear_elastic, density: 2300, youngs_modulus: 20e9, poisson_ratio: 0.2}
bodies:
  - name: target
    material: rock
    shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 0.015, length: 0.05}
  - name: jet
    material: cu
    jet:
      face: [0, 0.05]
      insert_distance: 0.01
      standoff: 0.03
      segments:
        - [1.0e-3, 4.0e-3, 8000, 0]
        - [1.2e-3, 4.0e-3, 6000, 1.0e-6]
)";
  const Scenario s = parse_deck(jet, "jet.yaml", {"bodies.1.jet.segments+=[[1.0e-3, 4.0e-3, 5000, 3.0e-6]]"});
  ASSERT_EQ(s.bodies[1].segments.size(), 3u);
  EXPECT_DOUBLE_EQ(s.bodies[1].segments[2].velocity[1], -5000.0);
  EXPECT_NEAR(s.bodies[1].segments[2].activation_time, 3e-6 + 0.02 / 5000, 1e-18);

  // A row inserted while the previous one still occupies the plane, found after reading from the
  // row's DeckMark: at the appended row with line 0, exactly as for the same row set with "=".
  const std::string bad = "[1.0e-3, 4.0e-3, 6000, 1.1e-6]";
  const DeckError e = parse_error(jet, {"bodies.1.jet.segments+=[" + bad + "]"});
  const DeckError e_set = parse_error(
      jet, {"bodies.1.jet.segments=[[1.0e-3, 4.0e-3, 8000, 0], [1.2e-3, 4.0e-3, 6000, 1.0e-6], " + bad + "]"});
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.key_path(), "bodies.1.jet.segments.2");
  EXPECT_TRUE(contains(e.what(), "still occupies the insertion plane")) << e.what();
  EXPECT_EQ(std::string(e.what()), std::string(e_set.what()));
}

TEST(DeckOverrideAppend, MapTargetIsAnError) {
  const DeckError e = parse_error(kDeck, {"simulation+={cfl: 0.2}"});
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.key_path(), "simulation");
  EXPECT_TRUE(contains(e.what(),
                       "in override 'simulation+={cfl: 0.2}': 'simulation' is a map, so '+=' cannot append to it "
                       "(it appends to lists); use simulation.KEY=value to set one of its entries"))
      << e.what();
  // A list element that is a map.
  const DeckError e2 = parse_error(kDeck, {"probes.0+=" + kKinetic});
  EXPECT_EQ(e2.key_path(), "probes.0");
  EXPECT_TRUE(contains(e2.what(), "'probes.0' is a map, so '+=' cannot append to it")) << e2.what();
}

TEST(DeckOverrideAppend, ScalarTargetIsAnError) {
  const DeckError e = parse_error(kDeck, {"simulation.end_time+=1"});
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.key_path(), "simulation.end_time");
  EXPECT_TRUE(contains(e.what(),
                       "in override 'simulation.end_time+=1': 'simulation.end_time' is a single value, so '+=' "
                       "cannot append to it (it appends to lists); use simulation.end_time=value to replace it"))
      << e.what();
  // A path through a single value fails as for "=".
  const DeckError e2 = parse_error(kDeck, {"simulation.end_time.x+=1"});
  EXPECT_TRUE(contains(e2.what(), "'simulation.end_time' is a single value, so it has no entry 'x'")) << e2.what();
  // So does an index out of range.
  const DeckError e3 = parse_error(kDeck, {"bodies.3.x+=1"});
  EXPECT_TRUE(contains(e3.what(), "index 3 is out of range: 'bodies' has 1 element")) << e3.what();
}

TEST(DeckOverrideAppend, SetAndAppendApplyInCommandLineOrder) {
  // "=" then "+=": the replaced list, then the appended item.
  const Scenario s = parse_deck(kDeck, "deck.yaml", {"probes=[" + kKinetic + "]", "probes+=" + kTipSpeed});
  EXPECT_EQ(probe_names(s), (std::vector<std::string>{"ke", "tip_speed"}));
  // "+=" then "=": the later "=" replaces the whole list, appended item included.
  const Scenario r = parse_deck(kDeck, "deck.yaml", {"probes+=" + kTipSpeed, "probes=[" + kKinetic + "]"});
  EXPECT_EQ(probe_names(r), (std::vector<std::string>{"ke"}));
}

TEST(DeckOverrideAppend, InvalidValueIsAnError) {
  const DeckError e = parse_error(kDeck, {"probes+={name: x, type: energy"});
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.key_path(), "probes");
  EXPECT_TRUE(contains(e.what(), "in override 'probes+={name: x, type: energy': value '{name: x, type: energy' is "
                                 "not valid YAML"))
      << e.what();
  // Nothing to append (an empty item is never a valid list entry).
  const DeckError e2 = parse_error(kDeck, {"probes+="});
  EXPECT_TRUE(contains(e2.what(), "in override 'probes+=': nothing to append after '+='")) << e2.what();
  const DeckError e3 = parse_error(kDeck, {"+=[1]"});
  EXPECT_TRUE(contains(e3.what(), "empty key path before '+='")) << e3.what();
}

TEST(DeckOverrideAppend, ValidationErrorsNameTheAppendingOverride) {
  // In an appended item: line 0 and the override, at the item's own index.
  const std::string bad = "probes+={name: len, type: extent, body: bar}";
  const DeckError e = parse_error(kDeck, {bad});
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.key_path(), "probes.2.axis");
  EXPECT_TRUE(contains(e.what(), "missing required key 'axis'")) << e.what();
  EXPECT_TRUE(contains(e.what(), "(value from override '" + bad + "')")) << e.what();

  // In one of the deck's own items, with an item appended: still the file's line, no override.
  std::string d = kDeck;
  d.replace(d.find("type: field_max"), 15, "type: field_mix");
  const DeckError e2 = parse_error(d, {"probes+=" + kTipSpeed});
  EXPECT_EQ(e2.line(), line_of(d, "field_mix"));
  EXPECT_EQ(e2.key_path(), "probes.1.type");
  EXPECT_FALSE(contains(e2.what(), "override")) << e2.what();

  // In a list "+=" created: the override too.
  const DeckError e3 = parse_error(deck_without_probes(), {bad});
  EXPECT_EQ(e3.line(), 0);
  EXPECT_EQ(e3.key_path(), "probes.0.axis");
  EXPECT_TRUE(contains(e3.what(), "(value from override '" + bad + "')")) << e3.what();

  // An item appended and then replaced by "=": the error names the "=" that set the value there.
  const std::string set =
      "probes=[" + kKinetic + ", {name: total, type: energy, field: total}, {name: z, type: extent}]";
  const DeckError e4 = parse_error(kDeck, {"probes+=" + kTipSpeed, set});
  EXPECT_EQ(e4.line(), 0);
  EXPECT_TRUE(contains(e4.what(), "(value from override '" + set + "')")) << e4.what();
}

}  // namespace test_override_append
