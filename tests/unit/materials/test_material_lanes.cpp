#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "materials/geomodel.hpp"
#include "materials/j2_plasticity.hpp"
#include "materials/johnson_cook.hpp"
#include "material_driver.hpp"

namespace test_material_lanes {

using namespace ballista;
using namespace ballista::test;

// The stress update kLanes points at a time (material_lanes.hpp) against the per-point loop of
// MaterialAdapter, and its independence of which points share a group of lanes.
namespace {

/// n points with random motion over one step; a few with a large stretch (distortion remap), a
/// large spin, or a poor rotation guess.
struct Points {
  FieldStore store;
  std::vector<Index> idx;
  explicit Points(const Material& m, Index n, std::mt19937& rng) {
    for (const char* f : {"F", "L", "R", "stress"}) store.add_real(f, 9, "1");
    for (const char* f : {"plastic_work", "volume0", "internal_energy", "plastic_energy"}) store.add_real(f, 1, "1");
    m.declare_fields(store);
    store.resize(n);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double dt = 1e-7;
    for (Index p = 0; p < n; ++p) {
      Mat3 F_old = Mat3::identity(), L, S;
      for (double& x : F_old.a) x += 0.2 * u(rng);
      if (p % 97 == 5) F_old = Mat3::diag(40.0, 1.0 / 40.0, 1.0) * F_old;  // beyond the limit below
      for (double& x : L.a) x = 2e5 * u(rng);
      if (p % 31 == 7) L = L + Mat3{{0, -3e6, 0, 3e6, 0, 0, 0, 0, 0}};  // 0.3 rad in one step
      for (double& x : S.a) x = 400e6 * u(rng);
      store.view<Mat3>("F")[p] = (Mat3::identity() + dt * L) * F_old;
      store.view<Mat3>("L")[p] = L;
      store.view<Mat3>("R")[p] = p % 53 == 3 ? rotation_about(Vec3{{0, 0, 1}}, 2.5) : polar_rotation(F_old);
      store.view<Mat3>("stress")[p] = sym(S);
      store.real("eqps")[p] = 0.1 * (1.0 + u(rng));
      store.real("volume0")[p] = 1e-9 * (1.5 + u(rng));
      store.real("internal_energy")[p] = 1e-3 * u(rng);
      store.real("plastic_energy")[p] = 1e-3 * (1.0 + u(rng));
    }
    // Every other point, so that the lanes gather from scattered indices; an odd count leaves a
    // short last group of lanes.
    for (Index p = 0; p < n; p += 2) idx.push_back(p);
  }
  void update(const Material& m, std::atomic<Index>& remaps) { update(m, remaps, idx); }
  /// `tangent`: a buffer for MaterialBatch::tangent, which keeps the batch on the per-point loop.
  void update(const Material& m, std::atomic<Index>& remaps, const std::vector<Index>& order,
              double* tangent = nullptr) {
    MaterialBatch b;
    b.tangent = tangent;
    b.points = order.data();
    b.count = static_cast<Index>(order.size());
    b.F_new = store.view<Mat3>("F");
    b.L = store.view<Mat3>("L");
    b.R = store.view<Mat3>("R");
    b.stress = store.view<Mat3>("stress");
    b.plastic_work = store.real("plastic_work");
    b.store = &store;
    b.dt = 1e-7;
    b.volume0 = store.real("volume0");
    b.internal_energy = store.real("internal_energy");
    b.plastic_energy = store.real("plastic_energy");
    b.distortion_limit = 20.0;
    b.distortion_remaps = &remaps;
    m.update(b);
  }
};

double max_abs(const Mat3& m) {
  double x = 0.0;
  for (double v : m.a) x = std::max(x, std::abs(v));
  return x;
}
double field_scale(const double* f, Index n) {
  double x = 0.0;
  for (Index p = 0; p < n; ++p) x = std::max(x, std::abs(f[p]));
  return x;
}
}  // namespace

// A material on the lane path, and the same material on the same points kept on the per-point
// loop by asking for the tangent (Johnson-Cook fills it beside the same stress; J2 then takes its
// general return instead of the closed form of the default configuration, the same algebra in
// another order). The two paths evaluate the same expressions, but the compiler fuses
// multiply-adds (FMA) differently in scalar and in vector code, so results agree to round-off, not
// bitwise: each fused or unfused operation differs by at most half an ulp, and a point's update is
// a chain of a few hundred operations on well-conditioned quantities (|R| = 1; the radial return
// scales the trial stress), hence the bounds of 1e-13 relative (about 500 ulps) below: of each
// tensor's largest entry, and of each scalar field's largest value over the points (an energy is a
// sum of terms of that size, and one that nearly cancels keeps their round-off). `fields` are the
// state fields compared besides F, R, the stress, the plastic work and the energies; returns the
// points of the lane path.
static std::unique_ptr<Points> lanes_against_per_point(const Material& m, Index n, unsigned seed,
                                                       const std::vector<const char*>& fields, const std::string& label) {
  std::mt19937 rng_a(seed), rng_b(seed);
  auto a = std::make_unique<Points>(m, n, rng_a);
  Points b(m, n, rng_b);
  std::vector<double> tangent(36 * static_cast<size_t>(n));
  std::atomic<Index> remaps_a{0}, remaps_b{0};
  a->update(m, remaps_a);
  b.update(m, remaps_b, b.idx, tangent.data());
  if (n > 100) {
    EXPECT_GT(remaps_a.load(), 0) << label;
  }
  EXPECT_EQ(remaps_a.load(), remaps_b.load()) << label;
  std::vector<const char*> scalars{"plastic_work", "internal_energy", "plastic_energy"};
  scalars.insert(scalars.end(), fields.begin(), fields.end());
  for (Index p = 0; p < n; ++p) {
    for (const char* f : {"F", "R", "stress"}) {
      const Mat3& x = a->store.view<Mat3>(f)[p];
      const Mat3& y = b.store.view<Mat3>(f)[p];
      EXPECT_LE(max_abs(x - y), 1e-13 * max_abs(y)) << label << ": " << f << " of point " << p;
    }
    for (const char* f : scalars) {
      const double x = a->store.real(f)[p], y = b.store.real(f)[p];
      EXPECT_LE(std::abs(x - y), 1e-13 * field_scale(b.store.real(f), n)) << label << ": " << f << " of point " << p;
    }
  }
  return a;
}

/// Points of `f` above zero.
static int count_positive(const Points& pts, const char* f, Index n) {
  int c = 0;
  for (Index p = 0; p < n; ++p) c += pts.store.real(f)[p] > 0.0;
  return c;
}

static void expect_paths_agree(const std::string& model, const ParamValues& v, const std::vector<const char*>& fields) {
  const auto m = make_material(model, v);
  for (const Index n : {Index{4003}, Index{9}}) {
    const auto a = lanes_against_per_point(*m, n, 3, fields, model);
    if (n > 100) {
      EXPECT_GT(count_positive(*a, "plastic_work", n), 100);  // both branches of the return are exercised
    }
  }
}

// J2's lane kernel (J2Plasticity::update_lanes).
TEST(MaterialLanes, J2StepIsThePerPointLoopToRoundOff) {
  const ParamValues v = j2_steel_values();
  ASSERT_TRUE(J2Plasticity::lanes_apply(J2Plasticity::make(v)));  // else the test compares a path with itself
  expect_paths_agree("j2_plasticity", v, {"eqps"});
}

// Johnson-Cook's scalar kernel lane by lane on the kinematics of kLanes points (copper with the
// Mie-Grueneisen EOS: the EOS energy is a state field too).
TEST(MaterialLanes, JohnsonCookStepIsThePerPointLoopToRoundOff) {
  const ParamValues v = JohnsonCook::example_params();
  ASSERT_TRUE(JohnsonCook::lanes_apply(JohnsonCook::make(v)));
  expect_paths_agree("johnson_cook", v, {"eqps", "temperature", "energy_density"});
}

// The geomodel's scalar kernel lane by lane (the Berea example: limit surface, cap, crush curve).
// Its returns iterate to tolerances, so a round-off difference could change an iteration count;
// the bound stays that of a round-off difference, which is what the points show.
TEST(MaterialLanes, GeomodelStepIsThePerPointLoopToRoundOff) {
  const ParamValues v = Geomodel::example_params();
  ASSERT_TRUE(Geomodel::lanes_apply(Geomodel::make(v)));
  const auto m = make_material("geomodel", v);
  const Index n = 4003;
  const auto a = lanes_against_per_point(*m, n, 3, {"eqps", "plastic_volumetric_strain"}, "geomodel");
  EXPECT_GT(count_positive(*a, "eqps", n), 100);  // the returns are exercised
}

// With a failure criterion that fires (max_stress at 350 MPa, erosion zero_stress: the stress
// zeroed, F and R set back to F_n and R_n). Bounds as above.
TEST(MaterialLanes, FailureAndErosionAreThePerPointLoopToRoundOff) {
  ParamValues v = JohnsonCook::example_params();
  v.choices["failure.criterion"] = "max_stress";
  v.choices["failure.erosion"] = "zero_stress";
  v["failure.max_stress"] = 350e6;
  const auto m = make_material("johnson_cook", v);
  const Index n = 4003;
  const auto a = lanes_against_per_point(*m, n, 9, {"eqps", "temperature", "damage", "failed"}, "failure");
  const int failed = count_positive(*a, "failed", n);
  EXPECT_GT(failed, 50);     // erosion is exercised ...
  EXPECT_LT(failed, n / 2);  // ... beside intact points
}

// A point's result does not depend on which points share its group of kLanes lanes (nor on the
// position of its lane): the batch in another order gives bitwise the same points. This is what
// keeps results independent of the thread count, the ranks and the sorting of the points.
TEST(MaterialLanes, APointDoesNotDependOnItsLaneNeighbours) {
  const auto m = make_material("j2_plasticity", j2_steel_values());
  std::mt19937 rng_a(5), rng_b(5);
  Points a(*m, 2001, rng_a), b(*m, 2001, rng_b);
  std::vector<Index> other(b.idx.rbegin(), b.idx.rend());  // reversed: new groups, new lanes
  std::rotate(other.begin(), other.begin() + 1, other.end());
  std::atomic<Index> ra{0}, rb{0};
  a.update(*m, ra);
  b.update(*m, rb, other);
  for (Index p = 0; p < 2001; ++p) {
    for (const char* f : {"F", "R", "stress"})
      EXPECT_EQ(std::memcmp(&a.store.view<Mat3>(f)[p], &b.store.view<Mat3>(f)[p], sizeof(Mat3)), 0) << f << " " << p;
    for (const char* f : {"eqps", "plastic_work", "internal_energy", "plastic_energy"})
      EXPECT_EQ(std::memcmp(&a.store.real(f)[p], &b.store.real(f)[p], sizeof(double)), 0) << f << " " << p;
  }
}

}  // namespace test_material_lanes
