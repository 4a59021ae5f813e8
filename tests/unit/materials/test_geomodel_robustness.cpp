// Robustness of the geomodel (issue 4, deliverable 3): 10^5 random large strain increments in
// tension and compression with random superimposed rotations, from random states reached by the
// same random walk, through the real MaterialAdapter. After every increment, for every point:
//   - stress and every state variable are finite (never NaN);
//   - the stress is on or inside the yield surface of its own state, f <= 1e-9 of the stress scale
//     (the return is solved to ~1e-13; 1e-9 leaves room for the rotation round trip of the
//     adapter and the consistency iteration's tolerance, and is far below any physical effect);
//   - porosity stays within [0, 1);
//   - the substep count stays within max_substeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "material_driver.hpp"
#include "materials/geomodel.hpp"

namespace ballista::test_geomodel_robustness {
namespace {

struct RobustnessStats {
  double worst_f = 0.0;  // largest f / scale seen
  int max_substeps = 0;
  double mean_substeps = 0.0;
  double min_porosity = 1.0, max_porosity = 0.0;
  double min_evp = 0.0, max_evp = 0.0;
};

/// Drives `points` points for `steps` random increments; strain increments have eigenvalues up to
/// +-`amplitude` (tension and compression), each step adds a rotation of up to 0.5 rad about a
/// random axis. A weak pull of the strain back toward zero (0.1 of ln J and 0.05 of dev(F F^T - I)
/// per step) keeps the random walk of F bounded (F invertible) without limiting single increments.
RobustnessStats drive_random(const ParamValues& v, int points, int steps, double amplitude, unsigned seed,
                             bool check_yield) {
  const Geomodel::Params prm = Geomodel::make(v);
  test::PointDriver d("geomodel", v, points);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RobustnessStats st;
  double substep_sum = 0.0;
  const double dt = 1e-6;
  d.set_dt(dt);
  for (int s = 1; s <= steps; ++s) {
    for (Index p = 0; p < points; ++p) {
      Mat3 H;
      for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j) H(i, j) = H(j, i) = amplitude * u(rng) * (i == j ? 1.0 : 0.5);
      const Mat3& F0 = d.F(p);
      const double pull_v = -0.1 * std::log(det(F0)) / 3.0;
      H += -0.05 * deviator(times_transpose(F0, F0));
      for (int i = 0; i < 3; ++i) H(i, i) += pull_v;
      Vec3 axis{{u(rng), u(rng), u(rng)}};
      axis = (1.0 / std::max(norm(axis), 1e-12)) * axis;
      const Mat3 Q = rotation_about(axis, 0.5 * u(rng));
      d.set_F(p, Q * (Mat3::identity() + H) * F0);
    }
    d.step(dt);
    for (Index p = 0; p < points; ++p) {
      const Mat3& sig = d.stress(p);
      EXPECT_TRUE(all_finite(sig)) << "point " << p << " step " << s;
      for (const auto& f : d.material().state_fields())
        EXPECT_TRUE(std::isfinite(d.state(f.name, p))) << f.name << " point " << p << " step " << s;
      const double evp = d.state("plastic_volumetric_strain", p);
      const double n = d.state("substeps", p);
      EXPECT_LE(n, prm.max_substeps);
      st.max_substeps = std::max(st.max_substeps, static_cast<int>(n));
      substep_sum += n;
      st.min_evp = std::min(st.min_evp, evp);
      st.max_evp = std::max(st.max_evp, evp);
      if (prm.crush.active()) {
        const double phi = d.state("porosity", p);
        EXPECT_GE(phi, 0.0);
        EXPECT_LT(phi, 1.0);
        st.min_porosity = std::min(st.min_porosity, phi);
        st.max_porosity = std::max(st.max_porosity, phi);
      }
      if (check_yield) {
        const double pf = Geomodel::pore_pressure(prm, evp);
        const GeoSurface surf = Geomodel::surface(prm, evp);
        const Mat3 dev = deviator(sig);
        const double rj2 = std::sqrt(0.5 * ddot(dev, dev));
        const double scale = frobenius(sig) + std::abs(prm.limit.a1) + 3.0 * pf + 1.0;
        const double f = surf.f(trace(sig) + 3.0 * pf, rj2) / scale;
        st.worst_f = std::max(st.worst_f, f);
        EXPECT_LE(f, 1e-9) << "point " << p << " step " << s << " I1' " << trace(sig) + 3.0 * pf << " sqrtJ2 " << rj2
                           << " evp " << evp;
      }
    }
    if (::testing::Test::HasFailure()) break;  // one diagnostic, not 10^5
  }
  st.mean_substeps = substep_sum / (double(points) * steps);
  return st;
}

void report(const char* name, const RobustnessStats& s) {
  std::printf("%s: worst f/scale %.2e, substeps max %d mean %.2f, porosity [%.4f, %.6f], evp [%.3f, %.3f]\n", name,
              s.worst_f, s.max_substeps, s.mean_substeps, s.min_porosity, s.max_porosity, s.min_evp, s.max_evp);
}

// The saturated, nonlinear, non-associative example (every feature on).
TEST(GeomodelRobustness, SaturatedNonlinearNonAssociative) {
  const RobustnessStats s = drive_random(Geomodel::example_params(), 1000, 100, 0.05, 1, true);  // 10^5 increments
  report("saturated", s);
  EXPECT_LT(s.min_evp, -0.05);  // the walk did reach heavy compaction ...
  EXPECT_GT(s.max_evp, 0.05);   // ... and dilatation
}

// Drained linear Drucker-Prager with cap, associative, pressure-dependent Poisson ratio; larger
// increments (eigenvalues up to +-0.15 per step).
TEST(GeomodelRobustness, DrainedLinearWithCapLargeIncrements) {
  ParamValues v{{"density", 2300.0}, {"bulk_modulus", 10e9},   {"bulk_modulus_gain", 6e9},
                {"bulk_modulus_i1_scale", 2e8}, {"shear_modulus", 7e9}, {"poisson_ratio_low", 0.2},
                {"poisson_ratio_gain", 0.1},    {"peak_i1", 30e6},      {"fslope", 0.5},
                {"cap_ratio", 0.5},             {"crush_p0", -300e6},   {"crush_p1", 5e-9},
                {"crush_p3", 0.2}};
  const RobustnessStats s = drive_random(v, 300, 100, 0.15, 2, true);
  report("drained", s);
  EXPECT_LT(s.min_porosity, 0.02);  // near full crush visited
}

// Rate dependence allows overstress (no yield check), but never NaN, bounded substeps and
// porosity in [0, 1) still hold.
TEST(GeomodelRobustness, RateDependentStaysFinite) {
  ParamValues v = Geomodel::example_params();
  v["relaxation_time"] = 2e-6;
  v["relaxation_rate_exponent"] = 0.1;
  const RobustnessStats s = drive_random(v, 200, 100, 0.05, 3, false);
  report("rate dependent", s);
}

}  // namespace
}  // namespace ballista::test_geomodel_robustness
