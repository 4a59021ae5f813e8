// The summary names the point that set the smallest stable time step (thesis ch. 6: collapsing
// time steps must be traceable to a particle): two free-flying elastic blocks, the faster one
// sets dt = CFL h / (c + |v|) with c the dilatational wave speed sqrt((K + 4G/3)/rho); on a
// graded grid the one whose signal crosses its own cell fastest. The tally of the limiter sampled over
// the run (run/step_tally.hpp): its counts, its checkpoint, and a run's statistics.step_set_by.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "core/error.hpp"
#include "run/step_tally.hpp"
#include "scenario/scenario.hpp"
#include "support/test_files.hpp"

namespace test_step_limiter {

using namespace ballista;

// Two aluminium blocks in free flight, `slow` at 10 m/s in x and `fast` at 300 m/s in y, with the
// given simulation and grid sections: the run's summary.json statistics.
YAML::Node free_flight_statistics(const std::string& simulation, const std::string& grid) {
  const std::string deck = "simulation: " + simulation + "\n" + grid + R"(
materials:
  al: {model: linear_elastic, density: 2700, bulk_modulus: 70e9, shear_modulus: 26e9}
bodies:
  - {name: slow, material: al, shape: {type: box, lower: [0.002, 0.002], upper: [0.006, 0.006]}, velocity: [10, 0]}
  - {name: fast, material: al, shape: {type: box, lower: [0.020, 0.002], upper: [0.024, 0.006]}, velocity: [0, 300]}
)";
  test::TempDir dir;
  RunOptions o;
  o.out_dir = dir.path.string();
  o.progress = false;
  const RunResult r = run_simulation(parse_deck(deck, "free_flight.yaml"), o);
  EXPECT_TRUE(r.ok) << r.error;
  return YAML::LoadFile((dir.path / "summary.json").string())["statistics"];
}

// The blocks on the given grid: the point named at the step's low.
YAML::Node limiter_of_run(const std::string& grid) {
  return free_flight_statistics("{dimension: plane_strain, end_time: 2.0e-7}", grid)["min_dt_set_by"];
}

TEST(StepLimiter, SummaryNamesTheFastestSignal) {
  const YAML::Node lim = limiter_of_run("grid: {lower: [0, 0], upper: [0.03, 0.01], cell_size: 1.0e-3}");
  ASSERT_TRUE(lim.IsMap());
  EXPECT_EQ(lim["body"].as<std::string>(), "fast");
  const double c = std::sqrt((70e9 + 4.0 * 26e9 / 3.0) / 2700.0);
  EXPECT_NEAR(lim["wave_speed"].as<double>(), c, 1e-9 * c);  // free flight: J = 1 to round-off
  EXPECT_NEAR(lim["speed"].as<double>(), 300.0, 1e-9);
  EXPECT_NEAR(lim["dt"].as<double>(), 0.3 * 1e-3 / (c + 300.0), 1e-12 * 1e-7);
}

// On a graded grid the step is CFL min_p l_p / (c_p + |v_p|) over each point's own cell: the slow
// block in 0.25 mm cells sets it, not the fast one in 1 mm cells (4 (c + 10) > c + 300).
TEST(StepLimiter, OnAGradedGridTheFastestSignalPerCellIsNamed) {
  const YAML::Node lim = limiter_of_run(
      "grid: {lower: [0, 0], upper: [0.03, 0.01], cell_size: 1.0e-3,"
      " refine: [{axis: x, from: 0.0, to: 0.008, cell_size: 0.25e-3}]}");
  ASSERT_TRUE(lim.IsMap());
  EXPECT_EQ(lim["body"].as<std::string>(), "slow");
  EXPECT_EQ(lim["signal"].as<std::string>(), "wave");
  EXPECT_NEAR(lim["cell"].as<double>(), 0.25e-3, 1e-12);
  const double c = std::sqrt((70e9 + 4.0 * 26e9 / 3.0) / 2700.0);
  EXPECT_NEAR(lim["speed"].as<double>(), 10.0, 1e-9);
  EXPECT_NEAR(lim["dt"].as<double>(), 0.3 * 0.25e-3 / (c + 10.0), 1e-12 * 1e-7);
}

}  // namespace test_step_limiter

namespace test_step_tally {

using namespace ballista;

StepLimiter limiter(std::int64_t id, int body, bool viscous, double J, double signal) {
  StepLimiter l;
  l.id = id;
  l.body = body;
  l.viscous = viscous;
  l.J = J;
  l.wave_speed = signal;
  return l;
}

// The tally counts samples per (body, signal), the distinct points up to its cap, and the range
// of J and the largest signal; the summary lists the entries by samples, shares summing to 1.
TEST(StepTally, CountsSamplesPointsAndRangesPerBodyAndSignal) {
  StepTally t;
  t.add(limiter(7, 1, false, 1.0, 5000.0));
  for (int k = 0; k < 3; ++k) {
    StepLimiter l = limiter(40 + k % 2, 0, true, 1.6 + 0.1 * k, 1.2e4 + k);
    l.margin = k == 0 ? 0.0 : 1.5 + k;  // the first without a margin (not computed)
    l.multirate = k == 0 ? 0.0 : 2.0 * k;  // nor a multi-rate figure
    t.add(l);
  }
  t.add(StepLimiter{});  // no particle: not a sample
  ASSERT_EQ(t.samples, 4);
  ASSERT_EQ(t.entries.size(), 2u);
  Scenario sc;
  sc.bodies.resize(2);
  sc.bodies[0].name = "jet";
  sc.bodies[1].name = "casing";
  const JsonValue j = t.json(sc);
  EXPECT_EQ(j.at("sample_interval").as_number(), static_cast<double>(kStepTallyInterval));
  EXPECT_DOUBLE_EQ(j.at("multirate_mean").as_number(), 3.0);  // (2 + 4) / 2: the samples that have one
  const JsonValue& first = j.at("entries").at(std::size_t{0});
  EXPECT_EQ(first.at("body").as_string(), "jet");
  EXPECT_EQ(first.at("signal").as_string(), "bulk_viscosity");
  EXPECT_DOUBLE_EQ(first.at("share").as_number(), 0.75);
  EXPECT_EQ(first.at("points").as_number(), 2.0);  // ids 40 and 41
  EXPECT_DOUBLE_EQ(first.at("J_min").as_number(), 1.6);
  EXPECT_DOUBLE_EQ(first.at("J_max").as_number(), 1.8);
  EXPECT_DOUBLE_EQ(first.at("signal_speed_max").as_number(), 1.2e4 + 2);
  EXPECT_DOUBLE_EQ(first.at("margin_mean").as_number(), 3.0);  // (2.5 + 3.5) / 2: the samples that have one
  const JsonValue& second = j.at("entries").at(std::size_t{1});
  EXPECT_FALSE(second.contains("margin_mean"));
  EXPECT_EQ(second.at("body").as_string(), "casing");
  EXPECT_DOUBLE_EQ(second.at("share").as_number(), 0.25);
}

TEST(StepTally, CapsTheDistinctPointsAndSurvivesACheckpoint) {
  StepTally t;
  for (std::int64_t id = 0; id < static_cast<std::int64_t>(kStepTallyMaxIds) + 5; ++id) {
    StepLimiter l = limiter(1000 - id, 2, false, 0.9, 4000.0);
    l.margin = 1.0 + 0.01 * static_cast<double>(id);
    l.multirate = 1.0 + 0.03 * static_cast<double>(id);
    t.add(l);
  }
  t.max_dt_samples = 3;
  t.add(limiter(3, 1, true, 0.5, 9000.0));
  ASSERT_EQ(t.entries[0].ids.size(), kStepTallyMaxIds);
  EXPECT_TRUE(t.entries[0].ids_capped);
  EXPECT_TRUE(std::is_sorted(t.entries[0].ids.begin(), t.entries[0].ids.end()));
  StateArchive a;
  t.save(a);
  StepTally back;
  back.load(a);
  ASSERT_EQ(back.samples, t.samples);
  EXPECT_EQ(back.max_dt_samples, 3);
  EXPECT_EQ(back.multirate_sum, t.multirate_sum);
  EXPECT_EQ(back.multirate_samples, t.multirate_samples);
  ASSERT_EQ(back.entries.size(), t.entries.size());
  for (std::size_t k = 0; k < t.entries.size(); ++k) {
    EXPECT_EQ(back.entries[k].body, t.entries[k].body);
    EXPECT_EQ(back.entries[k].viscous, t.entries[k].viscous);
    EXPECT_EQ(back.entries[k].samples, t.entries[k].samples);
    EXPECT_EQ(back.entries[k].ids, t.entries[k].ids);
    EXPECT_EQ(back.entries[k].ids_capped, t.entries[k].ids_capped);
    EXPECT_EQ(back.entries[k].J_min, t.entries[k].J_min);
    EXPECT_EQ(back.entries[k].J_max, t.entries[k].J_max);
    EXPECT_EQ(back.entries[k].signal_max, t.entries[k].signal_max);
    EXPECT_EQ(back.entries[k].margin_sum, t.entries[k].margin_sum);
    EXPECT_EQ(back.entries[k].margin_samples, t.entries[k].margin_samples);
  }
  StateArchive torn;  // an id count beyond the array: a clear error, not a read past its end
  torn.put("run.step_tally.ints", std::vector<std::int64_t>{1, 0, 1, 0, 0, 1, 0, 0, 5, 42});
  torn.put("run.step_tally.reals", std::vector<double>{1, 1, 1, 0});
  EXPECT_THROW(StepTally{}.load(torn), Error);
  StepTally old;  // a checkpoint written before the tally: empty
  old.add(limiter(1, 0, false, 1.0, 1.0));
  old.load(StateArchive{});
  EXPECT_EQ(old.samples, 0);
  EXPECT_TRUE(old.entries.empty());
}

// A run samples its limiter every kStepTallyInterval steps from step 0: in free flight the fast
// block sets every sample, all its points alike (margin 1: no few points hold the step); with a
// simulation.max_dt below the stable step no point sets it.
YAML::Node tally_of_free_flight(const std::string& simulation, long& steps) {
  const YAML::Node st = test_step_limiter::free_flight_statistics(
      simulation, "grid: {lower: [0, 0], upper: [0.03, 0.01], cell_size: 1.0e-3}");
  steps = st["steps"].as<long>();
  return st["step_set_by"];
}

TEST(StepTally, TheFreeFlightRunSamplesTheFastBlock) {
  long steps = 0;
  const YAML::Node tally = tally_of_free_flight("{dimension: plane_strain, end_time: 2.0e-6}", steps);
  ASSERT_TRUE(tally.IsMap());
  // Steps 0, 64, ... below the run's step count.
  EXPECT_EQ(tally["samples"].as<long>(), (steps - 1) / kStepTallyInterval + 1);
  EXPECT_EQ(tally["max_dt_samples"].as<long>(), 0);
  ASSERT_EQ(tally["entries"].size(), 1u);
  EXPECT_EQ(tally["entries"][0]["body"].as<std::string>(), "fast");
  EXPECT_EQ(tally["entries"][0]["signal"].as<std::string>(), "wave");
  EXPECT_DOUBLE_EQ(tally["entries"][0]["share"].as<double>(), 1.0);
  // Every point of the block alike to round-off (J = 1 in free flight).
  EXPECT_NEAR(tally["entries"][0]["margin_mean"].as<double>(), 1.0, 1e-12);
  // Both blocks' rates within 5 % of each other ((c + 300) / (c + 10), c = 6.2 km/s): one class,
  // nothing a per-point step would save.
  EXPECT_DOUBLE_EQ(tally["multirate_mean"].as<double>(), 1.0);
}

// On a graded grid the slow block's 256 points in 0.25 mm cells hold the step; the fast block's 64
// in 1 mm cells could take 4 (c + 10) / (c + 300) = 3.8 times it, rounded down to 2: a per-point
// step would update 256 + 64 / 2 points where one step for all updates 320, 10/9 as many.
TEST(StepTally, TheMultirateFigureCountsEachPointInTheClassOfItsOwnStep) {
  const YAML::Node st = test_step_limiter::free_flight_statistics(
      "{dimension: plane_strain, end_time: 2.0e-6}",
      "grid: {lower: [0, 0], upper: [0.03, 0.01], cell_size: 1.0e-3,"
      " refine: [{axis: x, from: 0.0, to: 0.008, cell_size: 0.25e-3}]}");
  ASSERT_EQ(st["particles"].as<long>(), 320);
  EXPECT_NEAR(st["step_set_by"]["multirate_mean"].as<double>(), 320.0 / 288.0, 1e-12);
}

TEST(StepTally, AStepSetByMaxDtIsNoPoints) {
  long steps = 0;
  const YAML::Node tally =
      tally_of_free_flight("{dimension: plane_strain, end_time: 2.0e-6, max_dt: 1.0e-8}", steps);
  ASSERT_TRUE(tally.IsMap());
  EXPECT_EQ(steps, 200);
  EXPECT_EQ(tally["samples"].as<long>(), 0);
  EXPECT_EQ(tally["max_dt_samples"].as<long>(), (steps - 1) / kStepTallyInterval + 1);
  EXPECT_EQ(tally["entries"].size(), 0u);
}

}  // namespace test_step_tally
