// Deck reader: rod and jet bodies (segments, insertion times), preparation stages and the
// penetration section (thesis seed 000 §5.1, §6.4).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"

namespace test_deck_penetrators {

using namespace ballista;

namespace {

// Axisymmetric: a target cylinder (top face at y = 0.05) and a penetrator above it.
std::string deck(const std::string& penetrator, const std::string& extra = "") {
  return R"(simulation: {dimension: axisymmetric, end_time: 1.0e-5}
grid: {lower: [0, 0, 0], upper: [0.02, 0.2, 0], cell_size: 1.0e-3}
materials:
  w: {model: linear_elastic, density: 17600, youngs_modulus: 350e9, poisson_ratio: 0.3}
  rock: {model: linear_elastic, density: 2300, youngs_modulus: 20e9, poisson_ratio: 0.2}
bodies:
  - name: target
    material: rock
    shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 0.015, length: 0.05}
  - name: pen
    material: w
)" + penetrator + extra;
}

std::string error_of(const std::string& text) {
  try {
    parse_deck(text, "pen.yaml");
  } catch (const DeckError& e) {
    return e.what();
  }
  return "";
}

TEST(DeckPenetrators, SolidRodIsOneSegmentWithItsSpeed) {
  const Scenario sc = parse_deck(deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n"), "r.yaml");
  const BodySpec& b = sc.bodies.at(1);
  ASSERT_EQ(b.segments.size(), 1u);
  EXPECT_EQ(b.penetrator.kind, "rod");
  EXPECT_DOUBLE_EQ(b.segments[0].shape.center[1], 0.052);  // flies towards -y: the base is the nose
  EXPECT_DOUBLE_EQ(b.segments[0].shape.length, 0.05);
  EXPECT_DOUBLE_EQ(b.segments[0].shape.radius, 2e-3);
  EXPECT_DOUBLE_EQ(b.segments[0].velocity[1], -1700.0);
  // A penetrator waits for the main stage; with no stages that is stage 0.
  EXPECT_EQ(b.activation_stage, 0);
}

TEST(DeckPenetrators, SegmentedRodKeepsItsMaterialLengthAndSpacing) {
  // Thesis §6.4: L = 50 mm, D = 4 mm cut into L/D = 1/2 pieces separated by voids of the same length.
  const Scenario sc = parse_deck(
      deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700, segment_ld: 0.5}\n"), "r.yaml");
  const BodySpec& b = sc.bodies.at(1);
  ASSERT_EQ(b.segments.size(), 25u);
  double total = 0.0;
  for (const auto& s : b.segments) total += s.shape.length;
  EXPECT_NEAR(total, 0.05, 1e-15);
  // Segment k starts k (L_seg + gap) = k * 4 mm behind the nose.
  EXPECT_NEAR(b.segments[3].shape.center[1], 0.052 + 3 * 4e-3, 1e-15);
  EXPECT_DOUBLE_EQ(b.penetrator.length, 0.05);
}

TEST(DeckPenetrators, JetSegmentsEnterAtTheirTimesAfterFreeFlight) {
  // standoff 30 mm, inserted 10 mm in front of the face at y = 0.05: a segment leaving the charge
  // plane at t0 arrives at the insertion plane at t0 + 20 mm / V.
  const Scenario sc = parse_deck(deck(R"(    jet:
      face: [0, 0.05]
      insert_distance: 0.01
      standoff: 0.03
      segments:
        - [1.0e-3, 4.0e-3, 8000, 0]
        - [1.2e-3, 4.0e-3, 6000, 1.0e-6]
)"),
                                 "j.yaml");
  const BodySpec& b = sc.bodies.at(1);
  ASSERT_EQ(b.segments.size(), 2u);
  EXPECT_NEAR(b.segments[0].activation_time, 0.02 / 8000, 1e-18);
  EXPECT_NEAR(b.segments[1].activation_time, 1e-6 + 0.02 / 6000, 1e-18);
  EXPECT_DOUBLE_EQ(b.segments[0].shape.center[1], 0.06);  // leading face on the insertion plane
  EXPECT_DOUBLE_EQ(b.segments[1].velocity[1], -6000.0);
  EXPECT_DOUBLE_EQ(b.penetrator.length, 8e-3);
  EXPECT_DOUBLE_EQ(b.penetrator.speed, 8000.0);
}

TEST(DeckPenetrators, JetSegmentInsertedOnTopOfTheLastOneIsAnError) {
  // Segment 0 needs 4 mm / 4000 m/s = 1 us to clear the plane; segment 1 comes at 0.5 us.
  const std::string e = error_of(deck(R"(    jet:
      face: [0, 0.05]
      insert_distance: 0.01
      segments:
        - [1.0e-3, 4.0e-3, 4000, 0]
        - [1.0e-3, 4.0e-3, 4000, 0.5e-6]
)"));
  EXPECT_NE(e.find("bodies.1.jet.segments.1"), std::string::npos) << e;
  EXPECT_NE(e.find("still occupies the insertion plane"), std::string::npos) << e;
}

TEST(DeckPenetrators, BadPenetratorInputsAreNamed) {
  EXPECT_NE(error_of(deck("    shape: {type: cylinder, center: [0, 0.06], axis: y, radius: 1e-3, length: 1e-2}\n"
                          "    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n"))
                .find("exactly one of shape"),
            std::string::npos);
  EXPECT_NE(error_of(deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n"
                          "    velocity: [0, -10]\n"))
                .find("gets its velocity"),
            std::string::npos);
  EXPECT_NE(error_of(deck("    rod: {nose: [0.001, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n"))
                .find("bodies.1.rod.nose"),
            std::string::npos);
  EXPECT_NE(error_of(deck("    rod: {nose: [0, 0.18], diameter: 4e-3, length: 0.05, speed: 1700}\n"))
                .find("outside the grid"),
            std::string::npos);
  EXPECT_NE(error_of(deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700, direction: 2}\n"))
                .find("expected 1"),
            std::string::npos);
  EXPECT_NE(error_of(deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700, gap: 1e-3}\n"))
                .find("segment_ld"),
            std::string::npos);
}

const std::string kStages = R"(stages:
  - name: overburden
    damping: 7.5e4
    min_duration: 1.0e-5
    max_duration: 5.0e-4
    until: {type: stress_equilibrium, body: target, stress: [-20e6, -30e6, -20e6]}
)";

TEST(DeckPenetrators, StagesAndPenetrationSection) {
  const Scenario sc = parse_deck(
      kStages + deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n",
                     "penetration: {penetrator: pen, target: target}\n"),
      "s.yaml");
  ASSERT_EQ(sc.stages.size(), 1u);
  EXPECT_EQ(sc.stages[0].until, "stress_equilibrium");
  EXPECT_DOUBLE_EQ(sc.stages[0].tolerance, 0.05);  // thesis §5.1: +-5 %
  EXPECT_DOUBLE_EQ(sc.stages[0].stress[1], -30e6);
  EXPECT_EQ(sc.bodies[0].activation_stage, 0);  // the target is there from the start
  EXPECT_EQ(sc.bodies[1].activation_stage, 1);  // the rod is fired in the main stage
  EXPECT_TRUE(sc.penetration.enabled);
  EXPECT_DOUBLE_EQ(sc.penetration.surface, 0.05);  // the target's top face, facing the rod
  EXPECT_DOUBLE_EQ(sc.penetration.axis_radius, 1e-3);
  // The resolved deck reads back to the same scenario.
  const Scenario again = parse_deck(sc.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(again.stages.size(), 1u);
  EXPECT_EQ(again.bodies[1].segments.size(), 1u);
  EXPECT_EQ(again.bodies[1].activation_stage, 1);
  EXPECT_TRUE(again.penetration.enabled);
}

TEST(DeckPenetrators, TheAxisRadiusIsOneCellOfTheBandsNotOfAPatch) {
  // A patch refines a box (here the target's top), not the path: the cavity's axis radius and the
  // stop tolerance keep the band's cell across the flight (0.5 mm), as the probe reads the jet's.
  std::string text = deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n",
                          "penetration: {penetrator: pen, target: target}\n");
  const std::string grid = "grid: {lower: [0, 0, 0], upper: [0.02, 0.2, 0], cell_size: 1.0e-3}";
  text.replace(text.find(grid), grid.size(),
               "grid: {lower: [0, 0, 0], upper: [0.02, 0.2, 0], cell_size: 1.0e-3, refine: [{axis: x, from: 0, to: "
               "0.004, cell_size: 0.5e-3}, {axis: y, from: 0.03, to: 0.06, cell_size: 0.5e-3}], patches: [{lower: "
               "[0, 0.04], upper: [0.004, 0.05], cell_size: 0.25e-3}]}");
  const Scenario sc = parse_deck(text, "p.yaml");
  ASSERT_EQ(sc.grid.patches.size(), 1u);
  EXPECT_DOUBLE_EQ(sc.penetration.axis_radius, 0.5e-3);
  EXPECT_DOUBLE_EQ(sc.penetration.stop_tolerance, 0.5e-3);
}

TEST(DeckPenetrators, StageErrorsAreNamed) {
  std::string bad = kStages;
  bad.replace(bad.find("body: target"), 12, "body: tagret");
  const std::string e = error_of(bad + deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n"));
  EXPECT_NE(e.find("stages.0.until.body"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'target'"), std::string::npos) << e;
  const std::string both = "stages:\n  - {name: a, duration: 1e-5, until: {type: stress_equilibrium, body: target, "
                           "stress: [-1e6, -1e6, -1e6]}, max_duration: 1e-4}\n";
  EXPECT_NE(error_of(both + deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n"))
                .find("not both"),
            std::string::npos);
  EXPECT_NE(error_of(deck("    rod: {nose: [0, 0.052], diameter: 4e-3, length: 0.05, speed: 1700}\n",
                          "penetration: {penetrator: target, target: pen}\n"))
                .find("is not a rod, a jet or a liner"),
            std::string::npos);
}

}  // namespace

}  // namespace test_deck_penetrators
