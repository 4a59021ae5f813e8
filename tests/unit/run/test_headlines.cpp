// What a penetration run prints about its depth (src/run/headlines.cpp): final when it ended
// because the penetrator was spent, "STILL MOVING" when it reached end_time with the penetration
// not stopped, and neither when the run did not complete (a failed or interrupted run's depth is
// neither final nor the depth at end_time); "NOT CONVERGED" with the cause, the penetrator's cells
// across its radius or a tunnel that runs on beyond the refined band; "UNPHYSICAL TENSION" for a
// material whose points were pulled beyond its cohesive limit (run/tension_watch.hpp); the tunnel's
// end as the depth when penetrator points lie far beyond it (analysis/beyond_tunnel.hpp); the level
// of the deck's grid study and how far it is from converged (analysis/convergence_statement.hpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "run/headlines.hpp"

namespace test_headlines {

using namespace ballista;

namespace {

JsonValue summary(const char* status, bool spent, bool stopped) {
  JsonValue s = JsonValue::object();
  s["status"] = status;
  JsonValue& p = s["penetration"];
  p = JsonValue::object();
  p["target"] = "rock";
  p["final_depth"] = 0.0487;
  p["final_cavity_depth"] = 0.0484;
  p["stop_time"] = stopped ? JsonValue(8.9e-5) : JsonValue();
  if (spent) {
    JsonValue& e = p["end_when_spent"];
    e = JsonValue::object();
    e["share"] = 1e-3;
    e["time"] = 8.92e-5;
  }
  return s;
}

int lines_with(const std::vector<std::string>& lines, const std::string& what) {
  int n = 0;
  for (const std::string& l : lines) n += l.find(what) != std::string::npos;
  return n;
}

TEST(Headlines, ASpentRunSaysItsDepthIsFinal) {
  const std::vector<std::string> l = headline_lines(summary("completed", true, true));
  EXPECT_EQ(lines_with(l, "depth into 'rock' = 48.7 mm"), 1);
  EXPECT_EQ(lines_with(l, "spent 89.2 us after firing"), 1);
  EXPECT_EQ(lines_with(l, "STILL MOVING"), 0);
}

TEST(Headlines, ARunStillPenetratingAtItsEndSaysSo) {
  const std::vector<std::string> l = headline_lines(summary("completed", false, false));
  EXPECT_EQ(lines_with(l, "STILL MOVING"), 1);
  EXPECT_EQ(lines_with(l, "is final"), 0);
  // Stopped before the end: nothing to say.
  const std::vector<std::string> s = headline_lines(summary("completed", false, true));
  EXPECT_EQ(lines_with(s, "STILL MOVING") + lines_with(s, "is final"), 0);
}

TEST(Headlines, AnUnfinishedRunMakesNoClaimAboutItsDepth) {
  for (const char* status : {"failed", "interrupted"})
    for (const bool spent : {true, false}) {
      const std::vector<std::string> l = headline_lines(summary(status, spent, false));
      EXPECT_EQ(lines_with(l, "STILL MOVING") + lines_with(l, "is final"), 0) << status << " spent " << spent;
      EXPECT_EQ(lines_with(l, "depth into"), 1) << status;
    }
}

TEST(Headlines, AnUnresolvedRunSaysWhy) {
  JsonValue thin = summary("completed", true, true);
  JsonValue& p = thin["penetration"];
  p["cells_across_radius"] = 1.0;
  p["resolved"] = false;
  std::vector<std::string> l = headline_lines(thin);
  EXPECT_EQ(lines_with(l, "NOT CONVERGED: the penetrator is 1 cells across its radius"), 1);
  // Four cells across, but the tunnel ends beyond the band: the band is the cause, not the radius.
  JsonValue past = summary("completed", true, true);
  JsonValue& q = past["penetration"];
  q["cells_across_radius"] = 4.0;
  q["resolved"] = false;
  JsonValue& c = q["path_cells"];
  c = JsonValue::object();
  c["finest"] = 0.25e-3;
  c["coarsest"] = 1.0e-3;
  c["coarser_from_depth"] = 0.130;
  JsonValue& t = q["tunnel"];
  t = JsonValue::object();
  t["depth"] = 0.1567;
  l = headline_lines(past);
  EXPECT_EQ(lines_with(l, "end 130.0 mm deep and the tunnel runs on to 156.7 mm in cells up to 1.0 mm"), 1);
  EXPECT_EQ(lines_with(l, "cells across its radius;"), 0);
  // Resolved: nothing to say.
  q["resolved"] = true;
  c["coarser_from_depth"] = JsonValue();
  EXPECT_EQ(lines_with(headline_lines(past), "NOT CONVERGED"), 0);
}

TEST(Headlines, AJetFormedInTheRunSaysItsConvergenceIsNotKnown) {
  // Its cells across the radius are not known before the run (null): no claim either way.
  JsonValue formed = summary("completed", false, false);
  JsonValue& p = formed["penetration"];
  p["formed_jet"] = true;
  p["cells_across_radius"] = JsonValue();
  p["resolved"] = false;
  std::vector<std::string> l = headline_lines(formed);
  EXPECT_EQ(lines_with(l, "CONVERGENCE NOT KNOWN: the jet formed in this run"), 1);
  EXPECT_EQ(lines_with(l, "NOT CONVERGED"), 0);
  // Without the key (a rod or a jet table) it says nothing of the kind.
  JsonValue rod = summary("completed", false, false);
  rod["penetration"]["cells_across_radius"] = JsonValue();
  rod["penetration"]["resolved"] = false;
  EXPECT_EQ(lines_with(headline_lines(rod), "CONVERGENCE NOT KNOWN"), 0);
}

}  // namespace

TEST(Headlines, PenetratorPointsBeyondTheTunnelDoNotSetTheDepth) {
  // 0.5 % of the jet 15 mm beyond the tunnel's end: the depth is the tunnel's, the points named.
  JsonValue s = summary("completed", true, true);
  JsonValue& p = s["penetration"];
  p["final_depth"] = 0.0634;
  JsonValue& b = p["beyond_tunnel"];
  b = JsonValue::object();
  b["tunnel_end"] = 0.0484;
  b["points"] = 3;
  b["mass_share"] = 0.005;
  std::vector<std::string> l = headline_lines(s);
  EXPECT_EQ(lines_with(l, "depth into 'rock' = 48.4 mm (the tunnel's end; the deepest penetrator point, 63.4 mm, "
                          "is one of 3 (0.5 % of its mass) beyond it"), 1);
  // None beyond: the deepest point is the depth, as before.
  b["points"] = 0;
  l = headline_lines(s);
  EXPECT_EQ(lines_with(l, "depth into 'rock' = 63.4 mm (cavity 48.4 mm)"), 1);
}

TEST(Headlines, TheGridStudySaysWhichLevelAndHowFar) {
  // A 2-cell level that the deck's study found within 5 %: the study's line, not the rule of thumb.
  JsonValue s = summary("completed", true, true);
  JsonValue& p = s["penetration"];
  p["cells_across_radius"] = 2.0;
  p["resolved"] = false;
  JsonValue& c = p["convergence"];
  c = JsonValue::object();
  c["record"] = "study.json";
  c["fingerprint_matches"] = true;
  c["level_cell"] = 0.5e-3;
  c["within"] = 0.036;
  JsonValue& q = c["quantities"];
  q = JsonValue::object();
  JsonValue depth = JsonValue::object();
  depth["label"] = "tunnel depth";
  depth["richardson"] = 0.1295;
  depth["level_gap"] = -0.036;
  q["cavity_depth"] = depth;
  std::vector<std::string> l = headline_lines(s);
  EXPECT_EQ(lines_with(l, "CONVERGED WITHIN 5 %: this is the 0.5 mm level of the deck's grid study, where it was "
                          "tunnel depth -3.6 % (129.5 mm converged) (study.json)"), 1);
  EXPECT_EQ(lines_with(l, "cells across its radius"), 0);
  // A failed run's depth is no level's answer: no claim.
  s["status"] = "failed";
  EXPECT_EQ(lines_with(headline_lines(s), "grid study"), 0);
  s["status"] = "completed";
  // A quantity the study could not converge (no Richardson estimate) keeps the level unconverged.
  JsonValue hole = JsonValue::object();
  hole["label"] = "casing hole";
  hole["converged_in_study"] = false;
  hole["richardson"] = JsonValue();
  hole["level_gap"] = JsonValue();
  c["quantities"]["casing_mean_hole"] = hole;
  c["all_converged"] = false;
  l = headline_lines(s);
  EXPECT_EQ(lines_with(l, "NOT CONVERGED: this is the 0.5 mm level of the deck's grid study, where it was tunnel "
                          "depth -3.6 % (129.5 mm converged), casing hole not converged in the study"), 1);
  // One with an estimate from too low an order says the order.
  c["quantities"]["casing_mean_hole"]["order"] = 0.42;
  c["quantities"]["casing_mean_hole"]["richardson"] = 0.0143;
  EXPECT_EQ(lines_with(headline_lines(s), "casing hole not converged in the study (observed order 0.42)"), 1);
  // A level the study ran for the hole alone (its finer levels, on the plates): the hole's gap is
  // within 5 %, the depth was not run there, so the level is not called converged.
  c["quantities"]["casing_mean_hole"]["converged_in_study"] = true;
  c["quantities"]["casing_mean_hole"]["order"] = 1.19;
  c["quantities"]["casing_mean_hole"]["richardson"] = 0.0133;
  c["quantities"]["casing_mean_hole"]["level_gap"] = -0.027;
  c["quantities"]["cavity_depth"]["level_gap"] = JsonValue();
  c["all_converged"] = true;
  c["within"] = 0.027;
  c["level_cell"] = 0.125e-3;
  EXPECT_EQ(lines_with(headline_lines(s), "NOT CONVERGED: this is the 0.125 mm level of the deck's grid study, where "
                                          "it was tunnel depth not run at this level, casing hole -2.7 % (13.3 mm "
                                          "converged)"),
            1);
  c["level_cell"] = 0.5e-3;
  c["quantities"]["cavity_depth"]["level_gap"] = -0.036;
  JsonValue& qq = c["quantities"];
  JsonValue only_depth = JsonValue::object();
  only_depth["cavity_depth"] = qq.at("cavity_depth");
  qq = only_depth;
  // 6 % from converged: not converged, by the study's measure.
  c["within"] = 0.06;
  c["quantities"]["cavity_depth"]["level_gap"] = -0.06;
  l = headline_lines(s);
  EXPECT_EQ(lines_with(l, "NOT CONVERGED: this is the 0.5 mm level"), 1);
  // Not a level of the study, or other physics: not known, and the rule of thumb speaks too.
  c["level_cell"] = JsonValue();
  l = headline_lines(s);
  EXPECT_EQ(lines_with(l, "are not a level of the deck's grid study (study.json)"), 1);
  EXPECT_EQ(lines_with(l, "NOT CONVERGED: the penetrator is 2 cells across its radius"), 1);
  c["fingerprint_matches"] = false;
  l = headline_lines(s);
  EXPECT_EQ(lines_with(l, "is of other physics than this run"), 1);
}

TEST(Headlines, PointsBeyondTheCohesiveLimitAreNamed) {
  JsonValue s = summary("completed", true, true);
  JsonValue& t = s["tension"];
  t = JsonValue::object();
  for (const char* name : {"jet_copper", "casing_steel"}) {
    JsonValue& m = t[name];
    m = JsonValue::object();
    m["cohesive_limit"] = -19.6e9;
    m["most_tensile_pressure"] = -150e9;
    m["most_tensile_time"] = 4.3e-5;
    m["most_points_beyond"] = std::string(name) == "jet_copper" ? 484.0 : 0.0;
  }
  const std::vector<std::string> l = headline_lines(s);
  EXPECT_EQ(lines_with(l, "UNPHYSICAL TENSION: up to 484 points of 'jet_copper'"), 1);
  EXPECT_EQ(lines_with(l, "-150 GPa at 43 us"), 1);
  EXPECT_EQ(lines_with(l, "casing_steel"), 0);  // within its limit: nothing to say
}

// A few points holding the stable step for most of the samples (run/step_tally.hpp) are named
// when the step without the fastest thousandth of the points would have been clearly larger; a
// step shared by many points, held for less than half the samples, over too few samples, with
// no such margin (ties in free flight) or with none known (peridynamics, OTM) is not news.
TEST(Headlines, AFewPointsHoldingTheStepAreNamed) {
  JsonValue s = summary("completed", true, true);
  JsonValue& st = s["statistics"];
  st = JsonValue::object();
  st["particles"] = 69293;
  st["step_set_by"]["samples"] = 181;
  JsonValue e = JsonValue::object();
  e["body"] = "jet";
  e["signal"] = "bulk_viscosity";
  e["share"] = 0.74;
  e["points"] = 4;
  e["points_at_least"] = false;
  e["J_min"] = 1.61;
  e["J_max"] = 1.83;
  e["signal_speed_max"] = 1.55e4;
  e["margin_mean"] = 1.9;
  auto with = [&](const JsonValue& entry) {
    JsonValue& entries = s["statistics"]["step_set_by"]["entries"];
    entries = JsonValue::array();
    entries.push_back(entry);
    return lines_with(headline_lines(s), "STEP HELD");
  };
  EXPECT_EQ(with(e), 1);
  EXPECT_EQ(lines_with(headline_lines(s),
                       "STEP HELD BY 4 POINTS: 74 % of the sampled steps were set by 4 points of 'jet' "
                       "(bulk-viscosity signal up to 1.55e+04 m/s, J 1.61 to 1.83); without the fastest thousandth "
                       "of the points the step would have been 1.9x larger there on average"),
            1);
  s["statistics"]["particles"] = 3000;  // 4 of 3,000 points: more than one in a thousand
  EXPECT_EQ(with(e), 0);
  s["statistics"]["particles"] = 69293;
  JsonValue f = e;
  f["share"] = 0.49;
  EXPECT_EQ(with(f), 0);
  f = e;
  f["margin_mean"] = 1.05;  // the next thousandth of the points nearly as fast: ties, no news
  EXPECT_EQ(with(f), 0);
  f = e;
  f["margin_mean"] = JsonValue();  // no margin known
  EXPECT_EQ(with(f), 0);
  f = e;
  f["points"] = 64;
  f["points_at_least"] = true;  // more distinct points than the tally counts: not a few
  EXPECT_EQ(with(f), 0);
  f["points_at_least"] = false;  // 64 of 69,293: a few
  EXPECT_EQ(with(f), 1);
  s["statistics"]["step_set_by"]["samples"] = 5;  // too few samples to say
  EXPECT_EQ(with(e), 0);
}

}  // namespace test_headlines
