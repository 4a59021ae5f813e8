// A point failed to zero stress (erosion zero_stress: no stress, F frozen; thesis seed 000
// eq. 6.13-6.14) has no stiffness, so it bounds MPM's stable step by its speed alone:
// dt = CFL l / max_p (c_p + |v_p|) with c_p = 0 for such a point. A failed point of a material
// whose failed points keep their stress (erosion none) keeps its wave speed. Two blocks in free
// flight on a uniform and on a graded grid: a soft slow one (c = 40.8 m/s, 10 m/s) and a steel
// one (c = 5.9 km/s, 300 m/s) whose points are marked failed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "deck/deck_reader.hpp"
#include "mpm/mpm_solver.hpp"
#include "run/simulation.hpp"

namespace test_stress_free_step {

using namespace ballista;

constexpr double kH = 1.0e-3;
constexpr double kCfl = 0.3;

std::unique_ptr<MpmSolver> solver_for(const std::string& erosion, bool graded) {
  std::string deck = R"(simulation: {dimension: plane_strain, end_time: 1.0e-6, cfl: 0.3}
grid: {lower: [0, 0], upper: [0.03, 0.01], cell_size: 1.0e-3)";
  // The graded grid's finest cells (0.5 mm) and their grading lie beyond both blocks.
  deck += graded ? ", refine: [{axis: x, from: 0.028, to: 0.03, cell_size: 0.5e-3}]}\n" : "}\n";
  deck += R"(materials:
  soft: {model: linear_elastic, density: 1000, bulk_modulus: 1.0e6, shear_modulus: 0.5e6}
  steel:
    model: linear_elastic
    density: 7850
    bulk_modulus: 160.0e9
    shear_modulus: 80.0e9
    failure: {criterion: max_stress, max_stress: 1.0e9, erosion: )" +
          erosion + R"(}
bodies:
  - {name: slow, material: soft, shape: {type: box, lower: [0.002, 0.002], upper: [0.006, 0.006]}, velocity: [10, 0]}
  - {name: debris, material: steel, shape: {type: box, lower: [0.010, 0.002], upper: [0.014, 0.006]}, velocity: [0, 300]}
)";
  const Scenario sc = parse_deck(deck, "stress_free_step.yaml");
  return std::make_unique<MpmSolver>(sc, make_materials(sc));
}

double p_wave_speed(double K, double G, double rho) { return std::sqrt((K + 4.0 * G / 3.0) / rho); }

void mark_steel_failed(MpmSolver& s) {
  FieldStore& p = s.points();
  double* failed = p.real("failed");
  const auto* body = p.ints("body");
  for (Index i = 0; i < p.size(); ++i)
    if (body[i] == 1) failed[i] = 1.0;
}

class StressFreeStep : public ::testing::TestWithParam<bool> {};

// Both blocks' points sit in cells of one length l (h on the uniform grid; the graded grid fits its
// coarse cells to the bands, 0.992 mm here), so marking the steel failed scales the step by
// (c_steel + 300) / 300 exactly, and on the uniform grid dt = CFL h / (c + |v|) in closed form
// (J = 1 at seeding: c to a few ulp).
TEST_P(StressFreeStep, AFailedStressFreePointBoundsTheStepByItsSpeedAlone) {
  const bool graded = GetParam();
  const double c_steel = p_wave_speed(160.0e9, 80.0e9, 7850.0);
  auto s = solver_for("zero_stress", graded);
  const double before = s->stable_dt();
  if (!graded) EXPECT_NEAR(before, kCfl * kH / (c_steel + 300.0), 1e-12 * before);
  mark_steel_failed(*s);
  // The steel points move at 300 m/s with no stiffness; the soft block's c + |v| is 50.8 m/s.
  const double after = s->stable_dt();
  EXPECT_NEAR(after / before, (c_steel + 300.0) / 300.0, 1e-12 * c_steel / 300.0);
  if (!graded) EXPECT_NEAR(after, kCfl * kH / 300.0, 1e-12 * after);
  const StepLimiter lim = s->step_limiter();
  EXPECT_EQ(lim.body, 1);
  EXPECT_EQ(lim.wave_speed, 0.0);
  EXPECT_NEAR(lim.speed, 300.0, 1e-9);
  EXPECT_FALSE(lim.viscous);
  if (graded) EXPECT_NEAR(after, kCfl * lim.cell / 300.0, 1e-12 * after);  // the cell it names
  else EXPECT_EQ(lim.cell, 0.0);
}

TEST_P(StressFreeStep, AFailedPointThatKeepsItsStressKeepsItsWaveSpeed) {
  auto s = solver_for("none", GetParam());
  const double before = s->stable_dt();
  mark_steel_failed(*s);
  EXPECT_EQ(s->stable_dt(), before);
  const double c_steel = p_wave_speed(160.0e9, 80.0e9, 7850.0);
  EXPECT_NEAR(s->step_limiter().wave_speed, c_steel, 1e-9 * c_steel);
}

INSTANTIATE_TEST_SUITE_P(UniformAndGraded, StressFreeStep, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "graded" : "uniform"; });

}  // namespace test_stress_free_step
