// The summary names the point that set the smallest stable time step (thesis ch. 6: collapsing
// time steps must be traceable to a particle): two free-flying elastic blocks, the faster one
// sets dt = CFL h / (c + |v|) with c the dilatational wave speed sqrt((K + 4G/3)/rho); on a
// graded grid the one whose signal crosses its own cell fastest.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_step_limiter {

using namespace ballista;

// Two aluminium blocks in free flight, `slow` at 10 m/s in x and `fast` at 300 m/s in y, on the
// given grid: the run's summary.json min_dt_set_by.
YAML::Node limiter_of_run(const std::string& grid) {
  const std::string deck = "simulation: {dimension: plane_strain, end_time: 2.0e-7}\n" + grid + R"(
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
  const RunResult r = run_simulation(parse_deck(deck, "limiter.yaml"), o);
  EXPECT_TRUE(r.ok) << r.error;
  return YAML::LoadFile((dir.path / "summary.json").string())["statistics"]["min_dt_set_by"];
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
