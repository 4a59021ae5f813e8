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

namespace ballista::test_otm_frozen_points {
namespace {

constexpr double kA = 1.0e3;    // 1/s: the converging velocity gradient
constexpr double kYc = 0.04;    // m: the block's mid-height

std::unique_ptr<OtmSolver> block(const std::string& erosion, bool failed) {
  const std::string deck =
      "simulation: {solver: otm, dimension: plane_strain, end_time: 1.0, cfl: 0.3}\n"
      "materials:\n"
      "  dust: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.25,\n"
      "         failure: {criterion: max_stress, max_stress: 1.0e9, erosion: " + erosion + "}}\n"
      "grid: {lower: [0.0, 0.0], upper: [0.1, 0.1], cell_size: 0.005}\n"
      "bodies:\n  - {name: block, material: dust, shape: {type: box, lower: [0.03, 0.03], upper: [0.06, 0.05]}}\n";
  const Scenario sc = parse_deck(deck, "otm_frozen_points.yaml");
  auto s = std::make_unique<OtmSolver>(sc, make_materials(sc));
  FieldStore& p = s->points();
  auto* v = p.view<Vec3>("v");
  const auto* x = p.view<Vec3>("x");
  double* f = p.real("failed");
  for (Index i = 0; i < p.size(); ++i) {
    v[i] = Vec3{{0.0, -kA * (x[i][1] - kYc), 0.0}};
    f[i] = failed ? 1.0 : 0.0;  // as if the criterion had been met in an earlier step
  }
  // The solver projected the bodies' (zero) velocity onto its nodes at construction; the test
  // gives them the converging field instead (the solver owns the nodes; nothing else writes them).
  auto& nodes = const_cast<otm::NodeCloud&>(s->nodes());
  for (std::size_t a = 0; a < nodes.v.size(); ++a) nodes.v[a] = Vec3{{0.0, -kA * (nodes.x[a][1] - kYc), 0.0}};
  return s;
}

double result(const OtmSolver& s, const std::string& name) {
  for (const auto& [k, v] : s.result_values())
    if (k == name) return v;
  return 0.0;  // absent: none
}

TEST(OtmFrozenPoints, AnInvertingIncrementOfAZeroStressPointIsDiscarded) {
  auto s = block("zero_stress", true);
  const FieldStore& p = s->points();
  const Index n = p.size();
  ASSERT_GT(n, 10);
  const double y_before = p.view<Vec3>("x")[0][1];
  ASSERT_NO_THROW(s->step(2.0 / kA));
  const auto* F = p.view<Mat3>("F");
  const auto* L = p.view<Mat3>("L");
  const auto* vol = p.real("volume");
  const auto* vol0 = p.real("volume0");
  for (Index i = 0; i < n; ++i) {
    // F_n = I kept exactly, so J = 1 and the volume is V0; the material saw no increment.
    for (int k = 0; k < 9; ++k) EXPECT_EQ(F[i].a[k], Mat3::identity().a[k]) << i;
    EXPECT_EQ(vol[i], vol0[i]) << i;
    for (double c : L[i].a) EXPECT_EQ(c, 0.0) << i;
  }
  // The points still move with their nodes: the lowest row, below the middle, to its mirror image
  // above it (by 2 |y - y_c|, more than a cell).
  EXPECT_GT(p.view<Vec3>("x")[0][1] - y_before, 0.005);
  EXPECT_EQ(result(*s, "frozen_increments_discarded"), static_cast<double>(n));
}

TEST(OtmFrozenPoints, APointThatHasNotFailedStillStopsTheRun) {
  auto s = block("zero_stress", false);
  EXPECT_THROW(s->step(2.0 / kA), ParticleError);
}

TEST(OtmFrozenPoints, AFailedPointThatKeepsAStressStillStopsTheRun) {
  // allow_no_shear keeps the pressure (eq. 6.12), so the point's deformation is not frozen.
  auto s = block("allow_no_shear", true);
  EXPECT_THROW(s->step(2.0 / kA), ParticleError);
}

}  // namespace
}  // namespace ballista::test_otm_frozen_points
