// Points deleted as they leave the grid (simulation.on_particle_exit: delete) are reported per
// body: summary.json's statistics count them, `deleted` books their mass and energy against the
// energy balance's removed terms, and a probe whose body has lost most of its mass is warned about.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_deletion_report {

namespace fs = std::filesystem;
using namespace ballista;

namespace {

// An aluminium ball (3D, r = 4 mm, 1 mm lattice: 280 particles of 1e-9 m^3) thrown at 300 m/s through the
// y_min face of the grid; a second ball at rest, inside.
const std::string kBalls =
    "simulation: {solver: mpm, dimension: 3d, end_time: 1.0e-4, on_particle_exit: delete}\n"
    "materials:\n  al: {model: linear_elastic, density: 2700, youngs_modulus: 70e9, poisson_ratio: 0.3}\n"
    "grid: {lower: [-0.01, -0.01, -0.01], upper: [0.02, 0.01, 0.01], cell_size: 2.0e-3}\n"
    "bodies:\n"
    "  - {name: ball, material: al, shape: {type: sphere, center: [0, 0.004, 0], radius: 0.004}, velocity: [0, -300, 0]}\n"
    "  - {name: still, material: al, shape: {type: sphere, center: [0.014, 0, 0], radius: 0.004}}\n"
    "probes:\n"
    "  - {name: still_velocity, type: mean_velocity, body: still, axis: y}\n"
    "  - {name: ball_velocity, type: mean_velocity, body: ball, axis: y}\n";

RunOptions quiet_run_options(const std::string& dir) {
  RunOptions o;
  o.out_dir = dir;
  o.threads = 1;
  o.progress = false;
  return o;
}

}  // namespace

TEST(DeletionReport, DeletedPointsAreCountedPerBodyAndTheProbeOfALostBodyIsWarned) {
  ballista::test::TempDir dir{"deletions"};
  // Ended while some particles of the ball remain (its front reaches the face at 33 us, its back
  // at 60 us).
  const RunResult r = run_simulation(parse_deck(kBalls, "balls.yaml", {"simulation.end_time=5.0e-5"}),
                                     quiet_run_options(dir.path.string()));
  ASSERT_TRUE(r.ok) << r.error;
  const YAML::Node s = YAML::LoadFile((dir.path / "summary.json").string());
  const double seeded = s["statistics"]["particles_seeded"].as<double>();
  const double deleted = s["statistics"]["particles_deleted"].as<double>();
  EXPECT_EQ(seeded, 560.0);  // two balls of 280
  EXPECT_GT(deleted, 140.0);  // most of the ball
  EXPECT_LT(deleted, 280.0);
  EXPECT_EQ(s["statistics"]["particles"].as<double>() + deleted, seeded);
  // All of it the ball's, and the deleted mass is the energy balance's removed mass.
  ASSERT_TRUE(s["deleted"]["ball"]);
  EXPECT_FALSE(s["deleted"]["still"]);
  EXPECT_EQ(s["deleted"]["ball"]["points"].as<double>(), deleted);
  EXPECT_NEAR(s["deleted"]["ball"]["mass_fraction"].as<double>() * 2700.0 * 280.0 * 1e-9,
              s["energy"]["removed_mass"].as<double>(), 1e-12 * s["energy"]["removed_mass"].as<double>());
  EXPECT_NEAR(s["deleted"]["ball"]["energy"].as<double>(), s["energy"]["removed_energy"].as<double>(), 1e-9);
  // Every warning of the run is in the summary (core/warning_log.hpp): the deletions as they
  // happened, then the probe's, logged last.
  const YAML::Node w = s["warnings"];
  ASSERT_GE(w.size(), 2u);
  EXPECT_NE(w[0].as<std::string>().find("points of body 'ball' left the grid and were deleted"), std::string::npos);
  EXPECT_NE(w[w.size() - 1].as<std::string>().find("probe 'ball_velocity' measures body 'ball', which has lost"),
            std::string::npos);
}

}  // namespace test_deletion_report
