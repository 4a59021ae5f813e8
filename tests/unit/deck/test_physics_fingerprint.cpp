// The fingerprint of a deck's physics (deck/physics_fingerprint.hpp) and the grid study's record
// a deck names (penetration.convergence_record): what a study varies between its levels leaves the
// fingerprint alone, a change of physics does not; a record that is missing or malformed is a deck
// error at its key. (tests/validate/check_convergence_record.py checks the script's hash is the
// run's and the statement a run makes with a record.)
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>

#include "deck/deck_reader.hpp"
#include "deck/physics_fingerprint.hpp"
#include "support/deck_errors.hpp"
#include "support/test_files.hpp"

namespace test_physics_fingerprint {

using namespace ballista;

const char* kDeck = R"(simulation: {dimension: axisymmetric, end_time: 1.0e-6}
grid: {lower: [0, 0], upper: [0.01, 0.04], cell_size: 1.0e-3}
materials:
  rock: {model: linear_elastic, density: 2300, youngs_modulus: 20e9, poisson_ratio: 0.2}
  w: {model: linear_elastic, density: 18400, youngs_modulus: 350e9, poisson_ratio: 0.3}
bodies:
  - {name: target, material: rock, shape: {type: cylinder, center: [0, 0], axis: y, radius: 0.008, length: 0.02}}
  - name: rod
    material: w
    rod: {nose: [0, 0.021], diameter: 2e-3, length: 4e-3, speed: 1000}
penetration: {penetrator: rod, target: target}
)";

std::string fingerprint(const std::vector<std::string>& overrides = {}) {
  return physics_fingerprint(parse_deck(kDeck, "deck.yaml", overrides).resolved_yaml);
}

TEST(PhysicsFingerprint, WhatAStudyVariesLeavesItAlone) {
  const std::string base = fingerprint();
  EXPECT_EQ(base.size(), 16u);
  EXPECT_EQ(fingerprint({"grid.cell_size=0.5e-3"}), base);  // the level (and the axis radius it sets)
  EXPECT_EQ(fingerprint({"grid.refine=[{axis: x, from: 0, to: 0.003, cell_size: 0.25e-3}]"}), base);
  EXPECT_EQ(fingerprint({"simulation.end_time=45e-6"}), base);
  EXPECT_EQ(fingerprint({"output.interval=1e-7", "output.checkpoint_interval=1e-7"}), base);
  EXPECT_EQ(fingerprint({"penetration.stop_tolerance=2e-3"}), base);
}

TEST(PhysicsFingerprint, APhysicsChangeChangesIt) {
  const std::string base = fingerprint();
  EXPECT_NE(fingerprint({"materials.w.density=18000"}), base);
  EXPECT_NE(fingerprint({"bodies.1.rod.speed=1100"}), base);
  EXPECT_NE(fingerprint({"simulation.cfl=0.2"}), base);
  EXPECT_NE(fingerprint({"penetration.end_when_spent=1e-3"}), base);
}

// A body of revolution is its outline: the resolved deck carries it (it re-reads to itself), so a
// changed vertex is a changed physics (a restart onto another section is refused by the same
// fingerprint), and the same outline written with other spellings of its numbers is the same.
TEST(PhysicsFingerprint, ABodyOfRevolutionIsItsOutline) {
  const std::string deck = R"(simulation: {dimension: axisymmetric, end_time: 1.0e-6}
grid: {lower: [0, 0], upper: [0.01, 0.04], cell_size: 1.0e-3}
materials:
  s: {model: linear_elastic, density: 7800, youngs_modulus: 200e9, poisson_ratio: 0.3}
bodies:
  - name: wall
    material: s
    shape: {type: revolution, center: [0, 0.01], axis: y, outline: [[0, 0], [0.008, 0], [0.008, 0.004], [0.003, 0.004], [0.003, 0.002], [0, 0.002]]}
)";
  const Scenario a = parse_deck(deck, "deck.yaml");
  EXPECT_NE(a.resolved_yaml.find("outline"), std::string::npos);
  EXPECT_EQ(parse_deck(a.resolved_yaml, "deck.yaml").resolved_yaml, a.resolved_yaml);
  const std::string base = physics_fingerprint(a.resolved_yaml);
  EXPECT_NE(physics_fingerprint(parse_deck(deck, "deck.yaml", {"bodies.0.shape.outline.4=[0.003, 0.0025]"}).resolved_yaml),
            base);
  std::string spelled = deck;
  spelled.replace(spelled.find("[0.008, 0.004]"), 14, "[8e-3, 4.0e-3]");
  EXPECT_EQ(physics_fingerprint(parse_deck(spelled, "deck.yaml").resolved_yaml), base);
}

TEST(PhysicsFingerprint, KeysAtNoneOrNullAreLeftOut) {
  // A key a newer build adds with a `none` or null default does not change what an older build ran.
  const std::string a = "simulation:\n  cfl: 0.5\nmaterials:\n  m:\n    eos:\n      min_pressure: -1\n";
  EXPECT_EQ(physics_fingerprint(a), physics_fingerprint(a + "      tension_cap: none\n      other: ~\n"));
  EXPECT_NE(physics_fingerprint(a), physics_fingerprint(a + "      tension_cap: cohesive_limit\n"));
  EXPECT_EQ(physics_fingerprint("# header\n" + a), physics_fingerprint(a));
}

TEST(ConvergenceRecord, AMissingOrMalformedRecordIsADeckErrorAtItsKey) {
  const DeckError missing = test::parse_error(kDeck, {"penetration.convergence_record=/nonexistent/record.json"});
  EXPECT_EQ(missing.key_path(), "penetration.convergence_record");
  EXPECT_NE(std::string(missing.what()).find("cannot open the grid study's record"), std::string::npos)
      << missing.what();
  test::TempDir dir;
  const std::string bad = (dir.path / "bad.json").string();
  std::ofstream(bad) << R"({"physics_fingerprint": "0123456789abcdef", "quantities": {"depth": {"richardson": 0.1}}})";
  const DeckError malformed = test::parse_error(kDeck, {"penetration.convergence_record=" + bad});
  EXPECT_EQ(malformed.key_path(), "penetration.convergence_record");
  EXPECT_NE(std::string(malformed.what()).find("quantity 'depth' needs summary_key, richardson and levels"),
            std::string::npos)
      << malformed.what();
  const std::string good = (dir.path / "good.json").string();
  std::ofstream(good) << R"({"physics_fingerprint": "0123456789abcdef", "study": "here", "quantities":
    {"depth": {"label": "tunnel depth", "summary_key": "final_cavity_depth", "richardson": 0.1, "order": 2,
               "levels": [[0.001, 0.08], [0.0005, 0.095]]}}})";
  const Scenario sc = parse_deck(kDeck, "deck.yaml", {"penetration.convergence_record=" + good});
  const ConvergenceRecord& r = sc.penetration.convergence;
  ASSERT_EQ(r.quantities.size(), 1u);
  EXPECT_EQ(r.fingerprint, "0123456789abcdef");
  EXPECT_EQ(r.quantities[0].summary_key, "final_cavity_depth");
  EXPECT_EQ(r.quantities[0].levels.size(), 2u);
  EXPECT_EQ(r.quantities[0].levels[1], std::make_pair(0.0005, 0.095));
  EXPECT_EQ(physics_fingerprint(sc.resolved_yaml), fingerprint());  // naming the record is not physics
}

TEST(ConvergenceRecord, AMalformedCheckedConfigurationIsADeckErrorAtItsKey) {
  // A checked configuration names quantities of the record, and one fingerprint is one configuration.
  const std::string head = R"({"physics_fingerprint": "0123456789abcdef", "quantities":
    {"depth": {"summary_key": "final_cavity_depth", "richardson": 0.1, "levels": [[0.001, 0.08]]}}, "checked": )";
  const std::pair<std::string, std::string> cases[] = {
      {R"({"a": {"configuration_fingerprint": "f1", "values": {"hole": 0.01}}})", "'hole' is not a quantity"},
      {R"({"a": {"values": {"depth": 0.09}}})", "needs configuration_fingerprint and values"},
      {R"({"a": {"configuration_fingerprint": "f1", "values": {"depth": 0.09}},
           "b": {"configuration_fingerprint": "f1", "values": {"depth": 0.091}}})",
       "have one fingerprint"},
      {R"([1, 2])", "'checked' is an object"}};
  test::TempDir dir;
  for (const auto& [checked, expected] : cases) {
    const std::string path = (dir.path / "record.json").string();
    std::ofstream(path) << head << checked << "}";
    const DeckError e = test::parse_error(kDeck, {"penetration.convergence_record=" + path});
    EXPECT_EQ(e.key_path(), "penetration.convergence_record") << checked;
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

}  // namespace test_physics_fingerprint
