// A solver is one folder and one registration: a discretisation defined here alone (as a new
// solver's files would be) is chosen by simulation.solver, reads its own deck section, and runs
// through `ballista run`'s loop to its outputs and summary without any other file naming it. The
// toy solver moves its points in free flight, x(t) = x0 + v t, the closed form it is checked
// against (the positions are sums of n steps of v dt: 1e-12 relative is round-off).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "deck/deck_reader.hpp"
#include "points/point_set.hpp"
#include "points/solver_registry.hpp"
#include "run/simulation.hpp"

namespace ballista {
namespace {

class FreeFlight final : public Solver {
 public:
  FreeFlight(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials)
      : pts_(sc, std::move(materials), SeedLattice{sc.grid, 0}, 0.0, ""),
        dt_(sc.solver_params.at("step")) {}
  const char* name() const override { return "test_free_flight"; }
  double stable_dt() override { return dt_; }
  void step(double dt) override {
    FieldStore& s = pts_.store();
    auto* x = s.view<Vec3>("x");
    const auto* v = s.view<Vec3>("v");
    for (Index p = 0; p < s.size(); ++p) x[p] += dt * v[p];
    time_ += dt;
    ++steps_;
  }
  double time() const override { return time_; }
  long steps() const override { return steps_; }
  FieldStore& points() override { return pts_.store(); }
  EnergyTotals energies() const override { return pts_.energies(1.0, 0.0); }
  double reporting_scale() const override { return 1.0; }
  void begin_stage(int stage, double) override { pts_.begin_stage(stage, time_); }

 private:
  PointSet pts_;
  double dt_;
  double time_ = 0.0;
  long steps_ = 0;
};

BALLISTA_REGISTER_SOLVER(SolverFactory{
    .name = "test_free_flight",
    .description = "points in free flight (test solver)",
    .dimensions = {"3d"},
    .section = "test_free_flight",
    .params = {ParamSpec{"step", "s", "time step", true, 0.0, 0.0, 1.0, true}},
    .create = [](const Scenario& sc, std::vector<std::unique_ptr<Material>> materials,
                 const Communicator&) -> std::unique_ptr<Solver> {
      return std::make_unique<FreeFlight>(sc, std::move(materials));
    }})

TEST(SolverRegistration, ASolverFromItsOwnFileRunsThroughTheRunLoop) {
  const std::string yaml = R"(
simulation: {solver: test_free_flight, dimension: 3d, end_time: 1.0e-3}
test_free_flight: {step: 1.0e-5}
materials:
  steel: {model: linear_elastic, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.3}
grid: {lower: [0, 0, 0], upper: [4.0e-3, 4.0e-3, 4.0e-3], cell_size: 1.0e-3}
bodies:
  - {name: block, material: steel, shape: {type: box, lower: [1.0e-3, 1.0e-3, 1.0e-3], upper: [3.0e-3, 3.0e-3, 3.0e-3]}, velocity: [3.0, -4.0, 12.0]}
probes:
  - {name: vx, type: mean_velocity, body: block, axis: x}
output: {interval: 5.0e-4}
)";
  const Scenario sc = parse_deck(yaml, "free_flight.yaml");
  const std::string out = (std::filesystem::temp_directory_path() / "ballista_free_flight").string();
  std::filesystem::remove_all(out);
  RunOptions opt;
  opt.out_dir = out;
  opt.progress = false;
  const RunResult r = run_simulation(sc, opt);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.steps, 100);
  EXPECT_NEAR(r.time, 1.0e-3, 1e-15);
  ASSERT_EQ(r.probes.size(), 1u);
  EXPECT_DOUBLE_EQ(r.probes[0].second, 3.0);  // the mean velocity is untouched by free flight
  // The loop's outputs: summary with the solver's name, history, the particle files.
  std::ifstream summary(out + "/summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"solver\": \"test_free_flight\""), std::string::npos) << text.substr(0, 400);
  EXPECT_TRUE(std::filesystem::exists(out + "/history.csv"));
  EXPECT_TRUE(std::filesystem::exists(out + "/particles_000002.h5"));
  // x = x0 + v t, from the final state.
  const Scenario sc2 = parse_deck(yaml, "free_flight.yaml");
  std::unique_ptr<Solver> s = make_solver(sc2);
  for (int k = 0; k < 100; ++k) s->step(s->stable_dt());
  const auto* x = s->points().view<Vec3>("x");
  const auto* x0 = s->points().view<Vec3>("x0");
  const Vec3 v{{3.0, -4.0, 12.0}};
  for (Index p = 0; p < s->points().size(); ++p)
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(x[p][a], x0[p][a] + v[a] * 1.0e-3, 1e-12 * (1.0 + std::abs(x0[p][a])));
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace ballista
