// run_simulation end to end on small decks: outputs land on the requested times, probes and the
// summary carry closed-form values, and failures (inverted particle, particle leaving the grid,
// energy drift) stop the run with a message naming the cause while earlier outputs stay intact.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_simulation {

namespace fs = std::filesystem;
using namespace ballista;

namespace {

RunOptions options(const fs::path& dir, int threads = 0) {
  RunOptions o;
  o.out_dir = dir.string();
  o.progress = false;
  o.threads = threads;
  return o;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Reads /time and the number of points (rows of /x) of one output file; false if unreadable.
bool read_h5(const fs::path& file, double& time, hsize_t& npoints) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return false;
  bool ok = false;
  const hid_t t = H5Dopen2(f, "/time", H5P_DEFAULT);
  if (t >= 0) {
    ok = H5Dread(t, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &time) >= 0;
    H5Dclose(t);
  }
  const hid_t x = H5Dopen2(f, "/x", H5P_DEFAULT);
  if (x >= 0) {
    const hid_t s = H5Dget_space(x);
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(s, dims, nullptr);
    npoints = dims[0];
    H5Sclose(s);
    H5Dclose(x);
  } else {
    ok = false;
  }
  H5Fclose(f);
  return ok;
}

const std::string kMaterials =
    "materials:\n"
    "  soft: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.25}\n"
    "  putty: {model: linear_elastic, density: 1000, youngs_modulus: 100, poisson_ratio: 0.25}\n";
const std::string kGrid2 = "grid: {lower: [0, 0], upper: [0.03125, 0.03125], cell_size: 0.00390625";

// A 3 x 3 cell block (ppc 2: 36 points) flying freely at [10, 0] m/s.
std::string flying_deck(const std::string& sim_extra = "", const std::string& loads = "") {
  return "simulation: {dimension: plane_strain, end_time: 1.0e-3" + sim_extra + "}\n" + kGrid2 + "}\n" + kMaterials +
         "bodies:\n  - {name: block, material: soft, velocity: [10, 0], shape: {type: box, lower: [0.00390625, 0.01171875], upper: [0.015625, 0.0234375]}}\n" +
         (loads.empty() ? "" : "loads:\n" + loads) +
         "probes:\n"
         "  - {name: length, type: extent, body: block, axis: x}\n"
         "  - {name: ke, type: energy, field: kinetic}\n"
         "output: {interval: 2.5e-4, history_every: 5}\n";
}

}  // namespace

TEST(RunSimulation, CompletedRunLandsOnOutputTimesAndReportsClosedFormProbes) {
  ballista::test::TempDir dir{"ballista_run"};
  const Scenario sc = parse_deck(flying_deck(), "flying.yaml");
  const RunResult r = run_simulation(sc, options(dir.path));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_NEAR(r.time, 1.0e-3, 1e-15);
  EXPECT_GT(r.steps, 10);
  // First output, every 2.5e-4 s, and the last: t = 0, 2.5e-4, 5e-4, 7.5e-4, 1e-3.
  const auto files = test::h5_files(dir.path);
  ASSERT_EQ(files.size(), 5u);
  for (size_t k = 0; k < files.size(); ++k) {
    double t = -1;
    hsize_t n = 0;
    ASSERT_TRUE(read_h5(files[k], t, n)) << files[k];
    EXPECT_NEAR(t, 2.5e-4 * k, 1e-15) << files[k];
    EXPECT_EQ(n, 36u);
  }
  EXPECT_TRUE(fs::exists(dir.path / "particles.xdmf"));
  // A rigidly flying block keeps its length (particle domains: exactly 3 cells) and its kinetic
  // energy 1/2 M v^2 (M = rho L^2 per metre); round-off only.
  ASSERT_EQ(r.probes.size(), 2u);
  EXPECT_EQ(r.probes[0].first, "length");
  EXPECT_NEAR(r.probes[0].second, 0.01171875, 1e-14);
  const double ke = 0.5 * 1000.0 * 0.01171875 * 0.01171875 * 100.0;
  EXPECT_NEAR(r.probes[1].second, ke, 1e-12 * ke);
  // summary.json (JSON is YAML): status, statistics and the same probe values.
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  EXPECT_EQ(s["status"].as<std::string>(), "completed");
  EXPECT_FALSE(s["error"]);
  EXPECT_EQ(s["statistics"]["steps"].as<long>(), r.steps);
  EXPECT_NEAR(s["probes"]["length"].as<double>(), r.probes[0].second, 1e-15);
  EXPECT_NEAR(s["energy"]["total"].as<double>(), ke, 1e-12 * ke);
  EXPECT_LT(s["statistics"]["worst_energy_drift"].as<double>(), 1e-12);
  // history.csv: a header with the probes and a row every 5 steps plus output/end rows.
  const std::string hist = slurp(dir.path / "history.csv");
  const std::string header = hist.substr(0, hist.find('\n'));
  EXPECT_NE(header.find("length"), std::string::npos) << header;
  EXPECT_NE(header.find("ke"), std::string::npos) << header;
  const long rows = std::count(hist.begin(), hist.end(), '\n') - 1;
  EXPECT_GE(rows, 1 + r.steps / 5);
  EXPECT_LE(rows, 1 + r.steps / 5 + 4);
  // resolved.yaml re-runs the same simulation.
  const Scenario again = parse_deck(slurp(dir.path / "resolved.yaml"), "resolved.yaml");
  EXPECT_EQ(again.simulation.end_time, sc.simulation.end_time);
  EXPECT_EQ(again.output.interval, sc.output.interval);
  EXPECT_EQ(again.bodies.at(0).velocity[0], 10.0);
}

TEST(RunSimulation, MaxStepsStopsTheRun) {
  ballista::test::TempDir dir{"ballista_run"};
  const RunResult r = run_simulation(parse_deck(flying_deck(", max_steps: 7"), "d.yaml"), options(dir.path, 1));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.steps, 7);
  EXPECT_LT(r.time, 1e-3);
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  EXPECT_EQ(s["statistics"]["steps"].as<long>(), 7);
  EXPECT_EQ(s["statistics"]["threads"].as<int>(), 1);
}

namespace {

// Two putty slabs (E = 100 Pa, c = 0.35 m/s) fly at each other at +-50 m/s with CFL 1. The
// stable step h / (c + 50) = 7.8e-5 s is capped at the output interval 5e-5 s. Once points of
// both slabs share grid cells (the 0.03125 m gap closes at t = 3.1e-4 s), the velocity jump
// across a cell, up to 100 m/s, compresses a point by dt |dv| / h > 1 in one step and its
// deformation gradient inverts, after seven regular outputs (t = 0, 5e-5, ..., 3e-4).
const std::string kPuttyDeck =
    "simulation: {dimension: plane_strain, end_time: 1.0e-3, cfl: 1.0}\n"
    "grid: {lower: [0, 0], upper: [0.0625, 0.03125], cell_size: 0.00390625}\n" +
    kMaterials +
    "bodies:\n"
    "  - {name: left, material: putty, velocity: [50, 0], shape: {type: box, lower: [0.00390625, 0.01171875], upper: [0.009765625, 0.01953125]}}\n"
    "  - {name: slab, material: putty, velocity: [-50, 0], shape: {type: box, lower: [0.041015625, 0.01171875], upper: [0.046875, 0.01953125]}}\n"
    "output: {interval: 5.0e-5}\n";
constexpr double kPuttyInterval = 5.0e-5;

}  // namespace

TEST(RunSimulation, InvertedParticleStopsTheRunAndKeepsEarlierOutputs) {
  ballista::test::TempDir dir{"ballista_run"};
  const RunResult r = run_simulation(parse_deck(kPuttyDeck, "putty.yaml"), options(dir.path));
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("inverted"), std::string::npos) << r.error;
  EXPECT_TRUE(r.error.find("of body 'slab'") != std::string::npos || r.error.find("of body 'left'") != std::string::npos) << r.error;
  EXPECT_NE(r.error.find("position ["), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("J = "), std::string::npos) << r.error;
  EXPECT_GT(r.time, 2.5e-4);  // not before the slabs meet
  EXPECT_LT(r.time, 1e-3);
  // summary.json: failed, with the same message.
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  EXPECT_EQ(s["status"].as<std::string>(), "failed");
  EXPECT_EQ(s["error"].as<std::string>(), r.error);
  // Earlier outputs are complete, readable and at their times; the failing state is one more.
  const auto files = test::h5_files(dir.path);
  ASSERT_GE(files.size(), 3u) << "the deck should produce at least two outputs before failing";
  for (size_t k = 0; k + 1 < files.size(); ++k) {
    double t = -1;
    hsize_t n = 0;
    ASSERT_TRUE(read_h5(files[k], t, n)) << files[k];
    EXPECT_EQ(n, 24u);  // 2 x (3 x 4) points
    EXPECT_NEAR(t, kPuttyInterval * k, 1e-15) << files[k];
  }
  double t_fail = -1;
  hsize_t n_fail = 0;
  ASSERT_TRUE(read_h5(files.back(), t_fail, n_fail)) << files.back();
  EXPECT_EQ(n_fail, 24u);
  EXPECT_NEAR(t_fail, r.time, 1e-15);
  for (const auto& e : fs::directory_iterator(dir.path)) EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

TEST(RunSimulation, FailingStateIsLabelledWithTheStepThatFailed) {
  // The failing state is written after positions and F were advanced by the failing step, so it
  // must carry that step's end time and number: its file time after the last regular output,
  // and the message's "at step N" equal to the steps reported (each step here is 5e-5 s).
  ballista::test::TempDir dir{"ballista_run"};
  const RunResult r = run_simulation(parse_deck(kPuttyDeck, "putty.yaml"), options(dir.path));
  ASSERT_FALSE(r.ok);
  const auto files = test::h5_files(dir.path);
  ASSERT_GE(files.size(), 2u);
  double t_last = -1, t_fail = -1;
  hsize_t n = 0;
  ASSERT_TRUE(read_h5(files[files.size() - 2], t_last, n));
  ASSERT_TRUE(read_h5(files.back(), t_fail, n));
  EXPECT_GT(t_fail, t_last) << "the failing state is labelled with the time of an earlier, different state";
  EXPECT_NEAR(r.time, kPuttyInterval * r.steps, 1e-15);
  EXPECT_NE(r.error.find("at step " + std::to_string(r.steps) + " "), std::string::npos) << r.error;
  EXPECT_EQ(static_cast<long>(files.size()), r.steps + 1) << "one output per step before the failure, plus the failing state";
}

TEST(RunSimulation, ParticleLeavingTheGridFailsTheRun) {
  ballista::test::TempDir dir{"ballista_run"};
  std::string yaml = flying_deck();
  yaml.replace(yaml.find("velocity: [10, 0]"), 17, "velocity: [40, 0]");  // leaves after ~0.4 ms
  const RunResult r = run_simulation(parse_deck(yaml, "exit.yaml"), options(dir.path));
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("left the grid box"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("of body 'block'"), std::string::npos) << r.error;
  // The rightmost column (x0 = 0.015625 - h/4) crosses x = 0.03125 at t = 0.0146484375 / 40.
  EXPECT_GT(r.time, (0.03125 - 0.015625 + 0.00390625 / 4) / 40.0);
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  EXPECT_EQ(s["status"].as<std::string>(), "failed");
}

TEST(RunSimulation, EnergyDriftLimitStopsARunThatLosesEnergy) {
  // A block hitting a fixed face loses kinetic energy that no term of the balance accounts
  // for (drift of order 1 after the impact): a limit of 1e-6 must stop it with a clear message.
  ballista::test::TempDir dir{"ballista_run"};
  const std::string yaml =
      "simulation: {dimension: plane_strain, end_time: 2.0e-3, energy_drift_limit: 1.0e-6}\n" + kGrid2 +
      ", boundary: {y_min: fixed}}\n" + kMaterials +
      "bodies:\n  - {name: block, material: soft, velocity: [0, -10], shape: {type: box, lower: [0.0078125, 0.0009765625], upper: [0.01953125, 0.0126953125]}}\n"
      "output: {history_every: 1}\n";
  const RunResult r = run_simulation(parse_deck(yaml, "drift.yaml"), options(dir.path));
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("energy drift"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("exceeds the limit"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("at step " + std::to_string(r.steps)), std::string::npos) << r.error;
  EXPECT_LT(r.time, 2.0e-3);
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  EXPECT_EQ(s["status"].as<std::string>(), "failed");
  EXPECT_GT(s["statistics"]["worst_energy_drift"].as<double>(), 1e-6);
}

TEST(RunSimulation, EnergyDriftLimitDoesNotTripOnAnExactBalance) {
  // A free block under gravity: the work of the body force equals the kinetic energy gained,
  // step by step, to round-off (see the solver tests), so even a tight limit of 1e-10 holds.
  ballista::test::TempDir dir{"ballista_run"};
  const RunResult r = run_simulation(
      parse_deck(flying_deck(", energy_drift_limit: 1.0e-10", "  - {type: body_force, acceleration: [0, -2000]}\n"),
                 "gravity.yaml"),
      options(dir.path));
  ASSERT_TRUE(r.ok) << r.error;
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  EXPECT_EQ(s["status"].as<std::string>(), "completed");
  EXPECT_LT(s["statistics"]["worst_energy_drift"].as<double>(), 1e-10);
  EXPECT_GT(s["energy"]["external_work"].as<double>(), 0.0);
}

}  // namespace test_simulation
