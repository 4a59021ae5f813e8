#pragma once
// The checks MPM's and OTM's frozen-point tests share (tests/unit/mpm/test_frozen_points.cpp,
// tests/unit/otm/test_otm_frozen_points.cpp): after a step whose increment inverts every point of a
// block failed under zero_stress, each point keeps F_n = I exactly (so J = 1 and its volume is
// V0), its material saw no increment (L = 0) and no stress, it still moved, and the summary counts
// every point; a point that has not failed, or one whose erosion keeps a stress, stops the run.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "support/solver_results.hpp"

namespace ballista::test {

/// The block's material: elastic dust failing at 1 GPa (never reached here) under `erosion`.
inline std::string dust_material(const std::string& erosion) {
  return "materials:\n"
         "  dust: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.25,\n"
         "         failure: {criterion: max_stress, max_stress: 1.0e9, erosion: " + erosion + "}}\n";
}

/// Gives the points the converging velocity v_y = -a (y - y_c) and marks them failed (as if the
/// criterion had been met in an earlier step) or not.
inline void converge_points(FieldStore& p, double a, double y_c, bool failed) {
  auto* v = p.view<Vec3>("v");
  const auto* x = p.view<Vec3>("x");
  double* f = p.real("failed");
  for (Index i = 0; i < p.size(); ++i) {
    v[i] = Vec3{{0.0, -a * (x[i][1] - y_c), 0.0}};
    f[i] = failed ? 1.0 : 0.0;
  }
}

/// `block(erosion, failed)` makes the solver with its block set up for the inverting step dt;
/// point 0 must move up by more than `moved_at_least` with its grid or nodes.
template <class MakeBlock>
void expect_inverting_step_discarded(MakeBlock block, double dt, double moved_at_least) {
  auto s = block("zero_stress", true);
  const FieldStore& p = s->points();
  const Index n = p.size();
  ASSERT_GT(n, 0);
  const double y_before = p.view<Vec3>("x")[0][1];
  ASSERT_NO_THROW(s->step(dt));
  const auto* F = p.view<Mat3>("F");
  const auto* L = p.view<Mat3>("L");
  const auto* stress = p.view<Mat3>("stress");
  const auto* vol = p.real("volume");
  const auto* vol0 = p.real("volume0");
  for (Index i = 0; i < n; ++i) {
    for (int k = 0; k < 9; ++k) EXPECT_EQ(F[i].a[k], Mat3::identity().a[k]) << i;
    EXPECT_EQ(vol[i], vol0[i]) << i;
    for (double c : L[i].a) EXPECT_EQ(c, 0.0) << i;
    for (double c : stress[i].a) EXPECT_EQ(c, 0.0) << i;
  }
  EXPECT_GT(p.view<Vec3>("x")[0][1] - y_before, moved_at_least);
  EXPECT_EQ(result_value(*s, "frozen_increments_discarded"), static_cast<double>(n));
}

/// The same block with points not frozen.
template <class MakeBlock>
void expect_unfrozen_inversions_stop(MakeBlock block, double dt) {
  EXPECT_THROW(block("zero_stress", false)->step(dt), ParticleError);
  // allow_no_shear keeps the pressure (eq. 6.12), so the point's deformation is not frozen.
  EXPECT_THROW(block("allow_no_shear", true)->step(dt), ParticleError);
}

}  // namespace ballista::test
