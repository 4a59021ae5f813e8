// A penetration run end to end in 3D (the axisymmetric path is covered by the example smoke
// tests): a segmented rod into a block, with the penetration section's outputs checked against
// bounds that hold for any solution: the depth never exceeds the free flight V t after contact,
// the penetrator never has more kinetic energy than it came with, and the files and summary
// keys are there.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "io/checkpoint_file.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_penetration_run {

using namespace ballista;

namespace {

// Quarter model: symmetry planes x = 0 and z = 0; the rod's axis is the y axis.
const char* kDeck = R"(simulation: {dimension: 3d, end_time: 4.0e-6}
mpm: {shape_function: gimp}
grid:
  lower: [0, -0.001, 0]
  upper: [0.006, 0.014, 0.006]
  cell_size: 0.5e-3
  boundary: {x_min: symmetry, z_min: symmetry}
materials:
  al: {model: j2_plasticity, density: 2700, youngs_modulus: 70e9, poisson_ratio: 0.33, yield_stress: 3e8}
  w: {model: linear_elastic, density: 17600, youngs_modulus: 350e9, poisson_ratio: 0.28}
bodies:
  - {name: block, material: al, shape: {type: box, lower: [0, 0, 0], upper: [0.005, 0.006, 0.005]}}
  - name: rod
    material: w
    rod: {nose: [0, 0.0065, 0], axis: y, direction: -1, diameter: 2e-3, length: 4e-3, speed: 800, segment_ld: 1.0, gap: 0.5e-3}
penetration: {penetrator: rod, target: block}
output: {history_every: 2}
)";

/// history.csv's column `name` as numbers.
std::vector<double> history_column(const std::filesystem::path& dir, const std::string& name) {
  std::ifstream h(dir / "history.csv");
  std::string header;
  std::getline(h, header);
  int col = -1, k = 0;
  for (size_t a = 0, b; a <= header.size(); a = b + 1, ++k) {
    b = header.find(',', a);
    if (b == std::string::npos) b = header.size();
    if (header.substr(a, b - a) == name) col = k;
  }
  std::vector<double> out;
  if (col < 0) return out;
  for (std::string line; std::getline(h, line);) {
    std::stringstream ss(line);
    std::string cell;
    for (int c = 0; c <= col; ++c) std::getline(ss, cell, ',');
    out.push_back(std::stod(cell));
  }
  return out;
}

TEST(PenetrationRun, ThreeDimensionalSegmentedRodIntoABlock) {
  test::TempDir dir;
  RunOptions o;
  o.out_dir = dir.path.string();
  o.progress = false;
  const Scenario sc = parse_deck(kDeck, "rod3d.yaml");
  ASSERT_EQ(sc.bodies[1].segments.size(), 2u);
  const RunResult r = run_simulation(sc, o);
  ASSERT_TRUE(r.ok) << r.error;
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  const YAML::Node p = s["penetration"];
  ASSERT_TRUE(p.IsMap());
  EXPECT_DOUBLE_EQ(p["surface"].as<double>(), 0.006);  // the block's face towards the rod
  EXPECT_EQ(p["segments"].as<int>(), 2);
  // The nose starts 0.5 mm above the face: after 4 us at 800 m/s free flight it would be
  // 2.7 mm deep; the block must slow it, and it must have entered.
  const double depth = p["max_depth"].as<double>();
  EXPECT_GT(depth, 0.0);
  EXPECT_LT(depth, 800.0 * 4.0e-6 - 0.5e-3);
  ASSERT_TRUE(p["arrival_time"].IsScalar());
  EXPECT_NEAR(p["arrival_time"].as<double>(), 0.5e-3 / 800.0, 0.5e-6);  // within the sampling
  // Penetrator kinetic energy: starts at 1/2 m V^2 of the quarter rod, never grows.
  const std::vector<double> ke = history_column(dir.path, "penetrator_kinetic_energy");
  ASSERT_FALSE(ke.empty());
  const double quarter_mass = 17600 * M_PI * 1e-6 * 4e-3 / 4;  // lattice seeding: +-10 % (checked below)
  const double first = ke.front(), last = ke.back();
  for (const double e : ke) EXPECT_LE(e, first * (1 + 1e-9));  // the block can only take energy from the rod
  EXPECT_NEAR(first, 0.5 * quarter_mass * 800.0 * 800.0, 0.1 * 0.5 * quarter_mass * 800.0 * 800.0);
  EXPECT_LT(last, first);
  EXPECT_TRUE(std::filesystem::exists(dir.path / "penetration.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir.path / "channel.csv"));
}


// Two soft copper segments flattening on a hard steel block (axisymmetric), the second inserted
// at 20 us, after the first is spent: their kinetic energy goes into plastic work within a few
// L/V = 10 us and never comes back beyond the elastic ringing, so penetration.end_when_spent must
// end the run after the second segment has come in and well before end_time.
const char* kSpentDeck = R"(simulation: {dimension: axisymmetric, end_time: 100.0e-6}
mpm: {shape_function: gimp, update: usavg}
grid:
  lower: [0, -0.001]
  upper: [0.008, 0.016]
  cell_size: 0.5e-3
  boundary: {x_min: symmetry}
materials:
  steel: {model: j2_plasticity, density: 7850, youngs_modulus: 200e9, poisson_ratio: 0.29, yield_stress: 1e9}
  cu: {model: j2_plasticity, density: 8960, youngs_modulus: 120e9, poisson_ratio: 0.34, yield_stress: 2e8}
bodies:
  - {name: block, material: steel, shape: {type: box, lower: [0, 0], upper: [0.006, 0.006]}}
  - name: jet
    material: cu
    jet: {face: [0, 0.006], axis: y, direction: -1, insert_distance: 4.0e-3,
          segments: [[1.5e-3, 3.0e-3, 300, 0], [1.5e-3, 3.0e-3, 300, 20.0e-6]]}
penetration: {penetrator: jet, target: block, end_when_spent: 0.05}
output: {history_every: 5, checkpoint_interval: 4.0e-6}
)";

TEST(PenetrationRun, EndsWhenThePenetratorIsSpentAndARestartEndsAtTheSameStep) {
  test::TempDir dir;
  RunOptions o;
  o.out_dir = dir.path.string();
  o.progress = false;
  o.threads = 1;
  const Scenario sc = parse_deck(kSpentDeck, "spent.yaml", {"output.checkpoint_keep=20"});
  const RunResult r = run_simulation(sc, o);
  ASSERT_TRUE(r.ok) << r.error;
  const YAML::Node p = YAML::LoadFile((dir.path / "summary.json").string())["penetration"];
  ASSERT_TRUE(p["end_when_spent"].IsMap());
  EXPECT_DOUBLE_EQ(p["end_when_spent"]["share"].as<double>(), 0.05);
  const double spent_at = p["end_when_spent"]["time"].as<double>();
  // The run ends at the first sample at which the energy is at most 5 % of its peak: that sample
  // is the history's last, and the one before it still held more.
  const std::vector<double> ke = history_column(dir.path, "penetrator_kinetic_energy");
  const std::vector<double> t = history_column(dir.path, "penetration_time");
  ASSERT_GE(ke.size(), 3u);
  double peak = 0.0;
  for (double e : ke) peak = std::max(peak, e);
  EXPECT_LE(ke.back(), 0.05 * peak);
  EXPECT_GT(ke[ke.size() - 2], 0.05 * peak);
  EXPECT_DOUBLE_EQ(t.back(), spent_at);
  // After the second segment came in (the first alone is spent by then), long before end_time.
  EXPECT_GT(spent_at, 20.0e-6);
  EXPECT_LT(spent_at, 60.0e-6);
  EXPECT_TRUE(p["stop_time"].IsScalar());  // a spent penetrator has stopped
  // Restarted from each of its checkpoints, the run ends at the same step with the same history.
  const std::string history = test::slurp(dir.path / "history.csv");
  const std::vector<std::string> cks = list_checkpoints(dir.path.string());
  ASSERT_GE(cks.size(), 6u);  // before and after the second segment came in
  for (const std::string& ck : cks) {
    test::TempDir copy("spent_copy");
    std::filesystem::copy(dir.path, copy.path, std::filesystem::copy_options::recursive);
    RunOptions c = o;
    c.out_dir = copy.path.string();
    c.restart_from = (copy.path / "checkpoints" / std::filesystem::path(ck).filename()).string();
    const RunResult again = run_simulation(sc, c);
    ASSERT_TRUE(again.ok) << again.error;
    EXPECT_EQ(again.steps, r.steps) << ck;
    EXPECT_TRUE(test::slurp(copy.path / "history.csv") == history) << "restart from " << ck;
  }
  // Without the key the same run goes on to its end_time and the summary has no such record.
  test::TempDir full;
  RunOptions f = o;
  f.out_dir = full.path.string();
  const Scenario without = parse_deck(kSpentDeck, "spent.yaml", {"penetration.end_when_spent=0", "simulation.end_time=30e-6"});
  ASSERT_TRUE(run_simulation(without, f).ok);
  const YAML::Node q = YAML::LoadFile((full.path / "summary.json").string())["penetration"];
  EXPECT_FALSE(q["end_when_spent"].IsDefined());
  EXPECT_NEAR(history_column(full.path, "penetration_time").back(), 30.0e-6, 1e-12);
}

TEST(PenetrationRun, EndWhenSpentIsAShareOfThePeak) {
  for (const char* bad : {"penetration.end_when_spent=1", "penetration.end_when_spent=-0.1"})
    EXPECT_THROW(parse_deck(kSpentDeck, "spent.yaml", {bad}), DeckError) << bad;
}

}  // namespace

}  // namespace test_penetration_run
