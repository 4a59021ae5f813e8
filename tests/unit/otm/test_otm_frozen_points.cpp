// OTM as MPM (tests/unit/mpm/test_frozen_points.cpp): a point eroded under `failure.erosion:
// zero_stress` keeps its deformation gradient (thesis seed 000 eq. 6.14, F* = F_n), so an increment
// of its nodes that would invert it is discarded, the run goes on and the summary counts it; a
// point that has not failed, or keeps a stress, still stops the run.
//
// The set-up forces the increment: the nodes of a plane-strain block get the converging velocity
// v_y = -a (y - y_c), and a step of dt = 2 / a moves each node to its mirror image about y_c, so
// the increment sum_a x_a^{k+1} (x) grad N_a (first-order consistency of the LME shape functions)
// is diag(1, -1, 1): inverted at every point.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "otm/otm_solver.hpp"
#include "run/simulation.hpp"
#include "support/frozen_points.hpp"

namespace ballista::test_otm_frozen_points {
namespace {

constexpr double kA = 1.0e3;    // 1/s: the converging velocity gradient
constexpr double kYc = 0.04;    // m: the block's mid-height

std::unique_ptr<OtmSolver> block(const std::string& erosion, bool failed) {
  const std::string deck =
      "simulation: {solver: otm, dimension: plane_strain, end_time: 1.0, cfl: 0.3}\n"
      + test::dust_material(erosion) +
      "grid: {lower: [0.0, 0.0], upper: [0.1, 0.1], cell_size: 0.005}\n"
      "bodies:\n  - {name: block, material: dust, shape: {type: box, lower: [0.03, 0.03], upper: [0.06, 0.05]}}\n";
  const Scenario sc = parse_deck(deck, "otm_frozen_points.yaml");
  auto s = std::make_unique<OtmSolver>(sc, make_materials(sc));
  test::converge_points(s->points(), kA, kYc, failed);
  // The solver projected the bodies' (zero) velocity onto its nodes at construction; the test
  // gives them the converging field instead (the solver owns the nodes; nothing else writes them).
  auto& nodes = const_cast<otm::NodeCloud&>(s->nodes());
  for (std::size_t a = 0; a < nodes.v.size(); ++a) nodes.v[a] = Vec3{{0.0, -kA * (nodes.x[a][1] - kYc), 0.0}};
  return s;
}

TEST(OtmFrozenPoints, AnInvertingIncrementOfAZeroStressPointIsDiscarded) {
  // Point 0, in the lowest row below the middle, goes to its mirror image above it: more than a cell.
  test::expect_inverting_step_discarded(block, 2.0 / kA, 0.005);
}

TEST(OtmFrozenPoints, AnInvertedPointThatIsNotFrozenStillStopsTheRun) {
  test::expect_unfrozen_inversions_stop(block, 2.0 / kA);
}

}  // namespace
}  // namespace ballista::test_otm_frozen_points
