// Issue 11 regressions at the run level: decks that cannot run (memory, runaway output, endless
// step counts) are refused before anything is allocated or written in bulk; results that are not
// numbers fail the run; a second run into the same folder leaves none of the first run's files.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/system_memory.hpp"
#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_run_guards {

namespace fs = std::filesystem;
using namespace ballista;

namespace {

RunOptions options(const fs::path& dir) {
  RunOptions o;
  o.out_dir = dir.string();
  o.progress = false;
  o.threads = 1;
  return o;
}

const std::string kMaterials =
    "materials:\n"
    "  soft: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.25}\n"
    "  putty: {model: linear_elastic, density: 1000, youngs_modulus: 100, poisson_ratio: 0.25}\n";

// A 3 x 3 cell block (ppc 2: 36 points) flying at [10, 0] m/s (as in test_simulation.cpp).
std::string deck(const std::string& sim_extra = "", const std::string& tail = "",
                 const std::string& material = "soft") {
  return "simulation: {dimension: plane_strain, end_time: 1.0e-3" + sim_extra + "}\n" +
         "grid: {lower: [0, 0], upper: [0.03125, 0.03125], cell_size: 0.00390625}\n" + kMaterials +
         "bodies:\n  - {name: block, material: " + material +
         ", velocity: [10, 0], shape: {type: box, lower: [0.00390625, 0.01171875], upper: [0.015625, 0.0234375]}}\n" +
         tail;
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(RunGuards, GridThatCannotFitIsRefusedWithTheFigureAndTheMachineMemory) {
  // 1.6e9 cells (under the reader's 2e9 limit) x ~104 B per node = ~170 GB: more than any machine
  // this runs on; it must be refused before the grid is allocated, not die in std::bad_alloc.
  ballista::test::TempDir dir{"ballista_guard"};
  const Scenario sc = parse_deck(
      "simulation: {end_time: 1.0e-6}\ngrid: {lower: [0, 0, 0], upper: [1, 1, 1], cell_size: 0.00085}\n" + kMaterials +
          "bodies:\n  - {name: b, material: soft, shape: {type: sphere, center: [0.5, 0.5, 0.5], radius: 0.002}}\n",
      "big.yaml");
  const SystemMemory mem = system_memory();
  ASSERT_GT(mem.total_bytes, 0.0);
  ASSERT_LT(mem.total_bytes, 1.0e11) << "this test assumes a machine with less than 100 GB";
  const std::string msg = error_of([&] { run_simulation(sc, options(dir.path)); });
  EXPECT_NE(msg.find("the run needs about"), std::string::npos) << msg;
  EXPECT_NE(msg.find("grid.cell_size"), std::string::npos) << msg;
  EXPECT_NE(msg.find(format_bytes(mem.total_bytes) + " in all"), std::string::npos) << msg;
}

TEST(RunGuards, RunawayOutputIntervalIsADeckError) {
  // 1e-3 s / 1e-12 s = 1e9 particle files.
  const std::string msg = error_of([] { parse_deck(deck("", "output: {interval: 1.0e-12}\n"), "d.yaml"); });
  EXPECT_NE(msg.find("'output.interval'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("output.max_outputs = 1000"), std::string::npos) << msg;
  // Insisting works: 20 files with max_outputs 25.
  EXPECT_NO_THROW(parse_deck(deck("", "output: {interval: 5.0e-5, max_outputs: 25}\n"), "d.yaml"));
  EXPECT_THROW(parse_deck(deck("", "output: {interval: 5.0e-5, max_outputs: 20}\n"), "d.yaml"), DeckError);
}

TEST(RunGuards, EndlessRunIsRefusedBeforeItStarts) {
  ballista::test::TempDir dir{"ballista_guard"};
  for (const std::string extra : {", cfl: 1.0e-12", ", max_dt: 1.0e-300"}) {
    const std::string msg = error_of([&] { run_simulation(parse_deck(deck(extra), "d.yaml"), options(dir.path)); });
    EXPECT_NE(msg.find("'simulation.step_limit'"), std::string::npos) << extra << ": " << msg;
    EXPECT_NE(msg.find("particle"), std::string::npos) << msg;  // names the point that sets dt
  }
  // The same deck at its default cfl runs: ~40 steps.
  const RunResult ok = run_simulation(parse_deck(deck(), "d.yaml"), options(dir.path));
  ASSERT_TRUE(ok.ok) << ok.error;
  // A limit just above the estimate is accepted; one below refuses.
  EXPECT_TRUE(run_simulation(parse_deck(deck(", step_limit: " + std::to_string(ok.steps + 5)), "d.yaml"),
                             options(dir.path))
                  .ok);
  EXPECT_THROW(
      run_simulation(parse_deck(deck(", step_limit: " + std::to_string(ok.steps / 2)), "d.yaml"), options(dir.path)),
      DeckError);
}

TEST(RunGuards, StepLimitStopsARunWhoseStepCollapsesLater) {
  // Putty (c = 0.35 m/s) accelerated at 100 m/s^2 from 1 m/s: |v| reaches 11 m/s, so the stable
  // step cfl h/(c + |v|) shrinks ~8x after the start. The first-step estimate is ~7 steps, the run
  // needs ~34 (integral of (c + |v|)/(cfl h) dt); a limit of 2/3 of the steps passes the start
  // check and stops the run with a diagnostic.
  ballista::test::TempDir dir{"ballista_guard"};
  auto accelerated = [](const std::string& extra) {
    return "simulation: {dimension: plane_strain, end_time: 0.1" + extra + "}\n" +
           "grid: {lower: [0, 0], upper: [1, 0.5], cell_size: 0.0625}\n" + kMaterials +
           "bodies:\n  - {name: block, material: putty, velocity: [1, 0], shape: {type: box, lower: [0.0625, 0.1875], "
           "upper: [0.25, 0.3125]}}\n"
           "loads:\n  - {type: body_force, acceleration: [100, 0]}\n";
  };
  const RunResult full = run_simulation(parse_deck(accelerated(""), "d.yaml"), options(dir.path));
  ASSERT_TRUE(full.ok) << full.error;
  const long limit = full.steps * 2 / 3;
  const RunResult r =
      run_simulation(parse_deck(accelerated(", step_limit: " + std::to_string(limit)), "d.yaml"), options(dir.path));
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.steps, limit);
  EXPECT_NE(r.error.find("simulation.step_limit"), std::string::npos) << r.error;
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  EXPECT_EQ(s["status"].as<std::string>(), "failed");
}

TEST(RunGuards, NonFiniteProbeFailsTheRun) {
  // A max_radius probe whose plane (y = 0.5 m) no particle comes near measures nothing: NaN. It
  // used to be written as null in a completed summary (and a centre at 1e308 gave inf, now a deck
  // error: the axis must cross the grid box). The run stops at its first history row in the loop.
  ballista::test::TempDir dir{"ballista_guard"};
  const RunResult r = run_simulation(
      parse_deck(deck("", "probes:\n  - {name: r, type: max_radius, body: block, axis: y, plane: 0.5, distance: "
                          "0.001, center: [0.01, 0, 0]}\n"),
                 "d.yaml"),
      options(dir.path));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("non-finite value in history.csv at step 1"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("'r' = nan"), std::string::npos) << r.error;
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  EXPECT_EQ(s["status"].as<std::string>(), "failed");
  EXPECT_NE(s["error"].as<std::string>().find("non-finite"), std::string::npos);
  const std::string msg = error_of([] {
    parse_deck(deck("", "probes:\n  - {name: r, type: max_radius, axis: y, distance: 0.001, center: [1.0e308, 0]}\n"),
               "d.yaml");
  });
  EXPECT_NE(msg.find("'probes.0.center'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("axis must pass through the grid box"), std::string::npos) << msg;
}

TEST(RunGuards, OverflowedHistoryValueStopsTheRun) {
  // The OTM Taylor bar with a density of 1.8e308 kg/m^3 (the largest double): a mass near 1e302 kg
  // whose energies stay finite and balanced, but whose wall reaction overflows to inf. The run must
  // stop at that row, not end "ok" with inf in history.csv (the fuzz found it).
  ballista::test::TempDir dir{"ballista_guard"};
  const RunResult r = run_simulation(
      read_deck(std::string(BALLISTA_SOURCE_DIR) + "/examples/taylor_bar_otm.yaml",
                {"materials.copper.density=1.7976931348623157e308", "simulation.end_time=1.0e-6",
                 "output.history_every=1"}),
      options(dir.path));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("non-finite value in history.csv"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("'wall_force' = inf"), std::string::npos) << r.error;
}

TEST(RunGuards, SecondRunIntoTheSameFolderLeavesNoStaleFiles) {
  ballista::test::TempDir dir{"ballista_guard"};
  // First run: 5 outputs. Then a stale temporary (a run killed mid-write) and a user's own file.
  ASSERT_TRUE(run_simulation(parse_deck(deck("", "output: {interval: 2.5e-4}\n"), "d.yaml"), options(dir.path)).ok);
  EXPECT_EQ(test::h5_files(dir.path).size(), 5u);
  std::ofstream(dir.path / "particles_000002.h5.tmp") << "partial";
  std::ofstream(dir.path / "notes.txt") << "mine";
  // Second run: first and last output only.
  ASSERT_TRUE(run_simulation(parse_deck(deck(), "d.yaml"), options(dir.path)).ok);
  EXPECT_EQ(test::h5_files(dir.path).size(), 2u);
  EXPECT_EQ(test::count_tmp(dir.path), 0);
  EXPECT_TRUE(fs::exists(dir.path / "notes.txt"));
}

}  // namespace test_run_guards
