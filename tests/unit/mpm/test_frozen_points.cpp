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
#include "support/frozen_points.hpp"

namespace test_frozen_points {

using namespace ballista;

constexpr double kA = 1.0e3;       // 1/s: the converging velocity gradient
constexpr double kYc = 0.013671875;  // m: the block's mid-height

std::unique_ptr<MpmSolver> block(const std::string& erosion, bool failed) {
  const std::string deck =
      "simulation: {dimension: plane_strain, end_time: 1.0, cfl: 0.3}\n"
      "mpm: {shape_function: linear, update: usl, flip: 1.0}\n"
      "grid: {lower: [-0.5, -0.5], upper: [0.5, 0.5], cell_size: 0.00390625}\n"
      + test::dust_material(erosion) +
      "bodies:\n"
      "  - {name: block, material: dust, shape: {type: box, lower: [0.0078125, 0.0078125], "
      "upper: [0.01953125, 0.01953125]}}\n";
  const Scenario sc = parse_deck(deck, "frozen_points.yaml");
  auto s = std::make_unique<MpmSolver>(sc, make_materials(sc));
  test::converge_points(s->points(), kA, kYc, failed);
  return s;
}

TEST(FrozenPoints, AnInvertingIncrementOfAZeroStressPointIsDiscarded) {
  // The points still move with the grid: the lowest row, 4.9 mm below the middle, upwards by
  // dt |v| = 9.8 mm in the interior field, by 7.6 mm with its edge nodes' blend; more than a cell.
  test::expect_inverting_step_discarded(block, 2.0 / kA, 0.00390625);
}

TEST(FrozenPoints, AnInvertedPointThatIsNotFrozenStillStopsTheRun) {
  test::expect_unfrozen_inversions_stop(block, 2.0 / kA);
}

TEST(FrozenPoints, AnOrdinaryIncrementOfAZeroStressPointIsUnchanged) {
  // dt = 0.5 / a: I + dt L = diag(1, 0.5, 1), not inverted; the point takes it in the kinematics
  // (its stress update then puts F_n back, eq. 6.14) and nothing is counted.
  auto s = block("zero_stress", true);
  s->step(0.5 / kA);
  const FieldStore& p = s->points();
  const auto* F = p.view<Mat3>("F");
  for (Index i = 0; i < p.size(); ++i) EXPECT_NEAR(F[i](1, 1), 1.0, 1e-9) << i;
  EXPECT_EQ(test::result_value(*s, "frozen_increments_discarded"), 0.0);
}

}  // namespace test_frozen_points
