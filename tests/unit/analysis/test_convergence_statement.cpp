// Which level of its deck's grid study a run is, and how far that level is from converged
// (src/analysis/convergence_statement.hpp), on the perforation demo's record: the depth studied at
// 1, 0.5 and 0.25 mm, the casing's hole on to 0.125 and 0.0625 mm. A level run for one quantity
// only says nothing of the other: all_at_level is false there, and the gap of the hole alone is
// not a claim about the depth. A configuration the study checked against its estimates (patches on
// the casing, a step per region) is named by its whole fingerprint and gives its own gaps.
#include <gtest/gtest.h>

#include "analysis/convergence_statement.hpp"

namespace test_convergence_statement {

using namespace ballista;

namespace {

/// The demo's record (examples/jet_casing_sandstone_mpm.convergence.json), rounded.
ConvergenceRecord demo_record() {
  ConvergenceRecord r;
  r.path = "demo.convergence.json";
  r.study = "docs/validation.md";
  r.fingerprint = "f";
  ConvergenceRecord::Quantity depth{"cavity_depth", "tunnel depth", "final_cavity_depth", 0.12944, 3.07,
                                    {{1e-3, 0.09146}, {5e-4, 0.12493}, {2.5e-4, 0.12891}}};
  ConvergenceRecord::Quantity hole{"casing_mean_hole",
                                   "casing hole",
                                   "holes.casing.mean_diameter",
                                   0.013296,
                                   1.19,
                                   {{1e-3, 0.011608}, {5e-4, 0.011834}, {2.5e-4, 0.012462}, {1.25e-4, 0.012932},
                                    {6.25e-5, 0.013137}}};
  r.quantities = {depth, hole};
  return r;
}

JsonValue penetration() {
  JsonValue p = JsonValue::object();
  p["final_cavity_depth"] = 0.125;
  return p;
}

}  // namespace

TEST(ConvergenceStatement, ALevelOfEveryQuantityGivesEachGap) {
  const JsonValue s = convergence_statement(demo_record(), "f", "c", 5e-4, penetration());
  EXPECT_EQ(s.at("level_cell").as_number(), 5e-4);
  EXPECT_TRUE(s.at("all_at_level").as_bool());
  EXPECT_TRUE(s.at("all_converged").as_bool());
  // 0.12493 / 0.12944 - 1 = -3.48 %, 0.011834 / 0.013296 - 1 = -11.0 %: the hole's is the larger.
  EXPECT_NEAR(s.at("quantities").at("cavity_depth").at("level_gap").as_number(), -0.0348, 1e-4);
  EXPECT_NEAR(s.at("within").as_number(), 0.1100, 1e-4);
  EXPECT_EQ(s.at("quantities").at("cavity_depth").at("run_value").as_number(), 0.125);
}

TEST(ConvergenceStatement, ALevelOfTheHoleAloneIsNotOneOfTheDepth) {
  const JsonValue s = convergence_statement(demo_record(), "f", "c", 1.25e-4, penetration());
  EXPECT_EQ(s.at("level_cell").as_number(), 1.25e-4);
  EXPECT_FALSE(s.at("all_at_level").as_bool());
  EXPECT_EQ(s.at("quantities").at("cavity_depth").at("level_value").kind(), JsonValue::Kind::Null);
  EXPECT_EQ(s.at("quantities").at("cavity_depth").at("level_gap").kind(), JsonValue::Kind::Null);
  // 0.012932 / 0.013296 - 1 = -2.74 %: the hole's gap, the only one measured at this level.
  EXPECT_NEAR(s.at("within").as_number(), 0.0274, 1e-4);
}

TEST(ConvergenceStatement, OtherPhysicsOrAnotherCellIsNoLevel) {
  const JsonValue other = convergence_statement(demo_record(), "g", "c", 5e-4, penetration());
  EXPECT_FALSE(other.at("fingerprint_matches").as_bool());
  EXPECT_EQ(other.at("level_cell").kind(), JsonValue::Kind::Null);
  EXPECT_FALSE(other.at("all_at_level").as_bool());
  const JsonValue between = convergence_statement(demo_record(), "f", "c", 3e-4, penetration());
  EXPECT_EQ(between.at("level_cell").kind(), JsonValue::Kind::Null);
  EXPECT_EQ(between.at("within").kind(), JsonValue::Kind::Null);
}

TEST(ConvergenceStatement, APatchedGridIsNoLevel) {
  // The study's 0.5 mm band with patches of finer cells on the casing: its hole is not the level's.
  const JsonValue patched = convergence_statement(demo_record(), "f", "c", 5e-4, penetration(), true);
  EXPECT_TRUE(patched.at("fingerprint_matches").as_bool());
  EXPECT_EQ(patched.at("level_cell").kind(), JsonValue::Kind::Null);
  EXPECT_EQ(patched.at("within").kind(), JsonValue::Kind::Null);
  EXPECT_FALSE(patched.at("all_at_level").as_bool());
}

TEST(ConvergenceStatement, ACheckedConfigurationGivesItsOwnGaps) {
  ConvergenceRecord r = demo_record();
  r.checked = {{"depth_run", "multi-rate", "m1", {{"cavity_depth", 0.1241}}},
               {"hole_run", "patches on the casing", "p1", {{"casing_mean_hole", 0.0127}}}};
  // The hole run's own summary: its hole is the recorded one.
  JsonValue hole_run = penetration();
  hole_run["holes"] = JsonValue::object();
  hole_run["holes"]["casing"] = JsonValue::object();
  hole_run["holes"]["casing"]["mean_diameter"] = 0.0127;
  // Its own physics fingerprint differs from the study's (the step per region is physics to it),
  // and its band is a level's: the configuration, not the level, is what it is.
  const JsonValue s = convergence_statement(r, "g", "p1", 5e-4, hole_run, true);
  EXPECT_EQ(s.at("checked").at("name").as_string(), "hole_run");
  EXPECT_EQ(s.at("level_cell").kind(), JsonValue::Kind::Null);
  // 0.0127 / 0.013296 - 1 = -4.48 %; the depth was not measured in this configuration.
  EXPECT_NEAR(s.at("quantities").at("casing_mean_hole").at("level_gap").as_number(), -0.0448, 1e-4);
  EXPECT_EQ(s.at("quantities").at("cavity_depth").at("level_value").kind(), JsonValue::Kind::Null);
  EXPECT_NEAR(s.at("within").as_number(), 0.0448, 1e-4);
  EXPECT_FALSE(s.at("all_at_level").as_bool());
  JsonValue depth_run = penetration();
  depth_run["final_cavity_depth"] = 0.1241;
  const JsonValue d = convergence_statement(r, "g", "m1", 5e-4, depth_run);
  EXPECT_EQ(d.at("checked").at("name").as_string(), "depth_run");
  EXPECT_NEAR(d.at("quantities").at("cavity_depth").at("level_gap").as_number(), 0.1241 / 0.12944 - 1, 1e-12);
  // Another configuration of the same physics at a level is that level, as without checked ones.
  const JsonValue level = convergence_statement(r, "f", "x", 5e-4, penetration());
  EXPECT_EQ(level.at("checked").kind(), JsonValue::Kind::Null);
  EXPECT_EQ(level.at("level_cell").as_number(), 5e-4);
}

TEST(ConvergenceStatement, ARunThatDoesNotReproduceACheckedConfigurationIsNotIt) {
  // The fingerprint leaves out the end time and the build: a run of the depth configuration
  // stopped early, or changed in its code, reads another depth, and the record's gap is not its.
  ConvergenceRecord r = demo_record();
  r.checked = {{"depth_run", "multi-rate", "m1", {{"cavity_depth", 0.1241}}}};
  JsonValue p = penetration();
  p["final_cavity_depth"] = 0.1241 * 1.021;  // just beyond the 2 % a build for another processor may move it
  const JsonValue s = convergence_statement(r, "g", "m1", 5e-4, p);
  EXPECT_EQ(s.at("checked").kind(), JsonValue::Kind::Null);
  EXPECT_EQ(s.at("within").kind(), JsonValue::Kind::Null);
  // The same code built for another instruction set: the deck as written's depth moved by 0.47 %
  // (AVX2 against the record's AVX-512 build), which is still the configuration.
  p["final_cavity_depth"] = 0.1241 * (1 + 0.0047);
  EXPECT_EQ(convergence_statement(r, "g", "m1", 5e-4, p).at("checked").at("name").as_string(), "depth_run");
  p["final_cavity_depth"] = 0.1241 * (1 - 0.019);
  EXPECT_EQ(convergence_statement(r, "g", "m1", 5e-4, p).at("checked").at("name").as_string(), "depth_run");
}

}  // namespace test_convergence_statement
