// Material::wave_speeds_at, the wave speeds of many points at given J with the state fields looked
// up once (the peridynamic gas's stable step), against wave_speed point by point.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "material_driver.hpp"

namespace ballista::test_eos_wave_speeds_at {
namespace {

// wave_speeds_at (the state fields looked up once) against wave_speed (looked up by name per
// point), for every registered model with an example parameter set: the same model call on the
// same state, so equal to the bit. Each point gets its own state values (random in [0.5, 1.5] of
// a unit scale, a burnt fraction and energies where the model has them) and its own J.
TEST(Material, WaveSpeedsAtAreThePointsWaveSpeeds) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  int models = 0;
  for (const MaterialFactory& f : material_registry()) {
    if (!f.example) continue;
    const auto m = f.create("test_" + f.model, f.example());
    FieldStore st;
    m->declare_fields(st);
    constexpr Index n = 64;
    st.resize(n);
    for (const StateFieldSpec& s : f.state_fields) {
      if (!st.has(s.name)) continue;
      double* v = st.real(s.name);
      const double base = std::isfinite(s.initial) && s.initial != 0.0 ? s.initial : 1.0;
      for (Index p = 0; p < n; ++p) v[p] = base * u(rng);
    }
    std::vector<Index> points;
    std::vector<double> J;
    for (Index p = n - 1; p >= 0; p -= 3) {  // not in order, not all of them
      points.push_back(p);
      J.push_back(u(rng));
    }
    std::vector<double> c(points.size());
    m->wave_speeds_at(st, points.data(), static_cast<Index>(points.size()), J.data(), c.data());
    for (size_t k = 0; k < points.size(); ++k) {
      const double want = m->wave_speed(st, points[k], J[k]);
      if (std::isnan(want))
        EXPECT_TRUE(std::isnan(c[k])) << f.model;
      else
        EXPECT_EQ(c[k], want) << f.model << " point " << points[k] << " J " << J[k];
    }
    ++models;
  }
  EXPECT_GE(models, 5);
}

}  // namespace
}  // namespace ballista::test_eos_wave_speeds_at
