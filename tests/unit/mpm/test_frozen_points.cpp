// Points eroded under `failure.erosion: zero_stress` keep their deformation gradient (thesis seed
// 000 eq. 6.14, F* = F_n): an increment of the grid that would invert such a stress-free point is
// discarded, the run goes on, and the summary counts it; every other inverted point still stops
// the run with the diagnostic.
//
// The set-up forces the increment. A plane-strain block of 6 x 6 points has the converging
// velocity v_y = -a (y - y_c); its grid velocity (linear weights, USL) is that field at the
// interior nodes and a mass-weighted blend of it at the block's edge nodes, so each point's L_yy
// is about -a, and a step of dt = 2 / a gives I + dt L ~ diag(1, -1, 1): an inverted increment
// for every point (all 36 are counted below).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "mpm/mpm_solver.hpp"
#include "run/simulation.hpp"

namespace test_frozen_points {

using namespace ballista;

constexpr double kA = 1.0e3;       // 1/s: the converging velocity gradient
constexpr double kYc = 0.013671875;  // m: the block's mid-height

std::unique_ptr<MpmSolver> block(const std::string& erosion, bool failed) {
  const std::string deck =
      "simulation: {dimension: plane_strain, end_time: 1.0, cfl: 0.3}\n"
      "mpm: {shape_function: linear, update: usl, flip: 1.0}\n"
      "grid: {lower: [-0.5, -0.5], upper: [0.5, 0.5], cell_size: 0.00390625}\n"
      "materials:\n"
      "  dust: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.25,\n"
      "         failure: {criterion: max_stress, max_stress: 1.0e9, erosion: " + erosion + "}}\n"
      "bodies:\n"
      "  - {name: block, material: dust, shape: {type: box, lower: [0.0078125, 0.0078125], "
      "upper: [0.01953125, 0.01953125]}}\n";
  const Scenario sc = parse_deck(deck, "frozen_points.yaml");
  auto s = std::make_unique<MpmSolver>(sc, make_materials(sc));
  FieldStore& p = s->points();
  auto* v = p.view<Vec3>("v");
  const auto* x = p.view<Vec3>("x");
  double* f = p.real("failed");
  for (Index i = 0; i < p.size(); ++i) {
    v[i] = Vec3{{0.0, -kA * (x[i][1] - kYc), 0.0}};
    f[i] = failed ? 1.0 : 0.0;  // as if the criterion had been met in an earlier step
  }
  return s;
}

bool same(const Mat3& a, const Mat3& b) {
  for (int k = 0; k < 9; ++k)
    if (a.a[k] != b.a[k]) return false;
  return true;
}

double result(const MpmSolver& s, const std::string& name) {
  for (const auto& [k, v] : s.result_values())
    if (k == name) return v;
  return 0.0;  // absent: none
}

TEST(FrozenPoints, AnInvertingIncrementOfAZeroStressPointIsDiscarded) {
  auto s = block("zero_stress", true);
  const FieldStore& p = s->points();
  const Index n = p.size();
  ASSERT_EQ(n, 36);
  const double y_before = p.view<Vec3>("x")[0][1];
  ASSERT_NO_THROW(s->step(2.0 / kA));
  const auto* F = p.view<Mat3>("F");
  const auto* L = p.view<Mat3>("L");
  const auto* stress = p.view<Mat3>("stress");
  const auto* vol = p.real("volume");
  const auto* vol0 = p.real("volume0");
  for (Index i = 0; i < n; ++i) {
    // F_n = I kept exactly (nothing is computed from it), so J = 1 and the volume is V0.
    EXPECT_TRUE(same(F[i], Mat3::identity())) << i;
    EXPECT_EQ(vol[i], vol0[i]) << i;
    EXPECT_TRUE(same(L[i], Mat3{})) << i;  // the material saw no increment
    for (double c : stress[i].a) EXPECT_EQ(c, 0.0) << i;
  }
  // The points still move with the grid: the lowest row, 4.9 mm below the middle, upwards by
  // dt |v| = 9.8 mm in the interior field, by 7.6 mm with its edge nodes' blend; more than a cell.
  EXPECT_GT(p.view<Vec3>("x")[0][1] - y_before, 0.00390625);
  EXPECT_EQ(result(*s, "frozen_increments_discarded"), static_cast<double>(n));
}

TEST(FrozenPoints, APointThatHasNotFailedStillStopsTheRun) {
  auto s = block("zero_stress", false);
  EXPECT_THROW(s->step(2.0 / kA), ParticleError);
}

TEST(FrozenPoints, AFailedPointThatKeepsAStressStillStopsTheRun) {
  // allow_no_shear keeps the pressure (eq. 6.12), so the point's deformation is not frozen.
  auto s = block("allow_no_shear", true);
  EXPECT_THROW(s->step(2.0 / kA), ParticleError);
}

TEST(FrozenPoints, AnOrdinaryIncrementOfAZeroStressPointIsUnchanged) {
  // dt = 0.5 / a: I + dt L = diag(1, 0.5, 1), not inverted; the point takes it in the kinematics
  // (its stress update then puts F_n back, eq. 6.14) and nothing is counted.
  auto s = block("zero_stress", true);
  s->step(0.5 / kA);
  const FieldStore& p = s->points();
  const auto* F = p.view<Mat3>("F");
  for (Index i = 0; i < p.size(); ++i) EXPECT_NEAR(F[i](1, 1), 1.0, 1e-9) << i;
  EXPECT_EQ(result(*s, "frozen_increments_discarded"), 0.0);
}

}  // namespace test_frozen_points
