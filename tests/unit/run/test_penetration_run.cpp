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

#include "deck/deck_reader.hpp"
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
  std::ifstream h(dir.path / "history.csv");
  std::string header;
  std::getline(h, header);
  int col = -1, k = 0;
  for (size_t a = 0, b; a <= header.size(); a = b + 1, ++k) {
    b = header.find(',', a);
    if (b == std::string::npos) b = header.size();
    if (header.substr(a, b - a) == "penetrator_kinetic_energy") col = k;
  }
  ASSERT_GE(col, 0);
  const double quarter_mass = 17600 * M_PI * 1e-6 * 4e-3 / 4;  // lattice seeding: +-10 % (checked below)
  double first = -1, last = 0;
  for (std::string line; std::getline(h, line);) {
    std::stringstream ss(line);
    std::string cell;
    for (int c = 0; c <= col; ++c) std::getline(ss, cell, ',');
    const double e = std::stod(cell);
    if (first < 0) first = e;
    EXPECT_LE(e, first * (1 + 1e-9));  // the block can only take energy from the rod
    last = e;
  }
  EXPECT_NEAR(first, 0.5 * quarter_mass * 800.0 * 800.0, 0.1 * 0.5 * quarter_mass * 800.0 * 800.0);
  EXPECT_LT(last, first);
  EXPECT_TRUE(std::filesystem::exists(dir.path / "penetration.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir.path / "channel.csv"));
}

}  // namespace

}  // namespace test_penetration_run
