#pragma once
// A FieldStore of n points laid out as a solver holds them (F, R, L, stress, reference volume,
// energy accumulators, the material's state fields) and the MaterialBatch over all of them: the
// common set-up of the material benchmarks.
#include <numeric>
#include <vector>

#include "core/field_store.hpp"
#include "materials/material.hpp"

namespace ballista::bench {

struct MaterialBatchFixture {
  FieldStore store;
  std::vector<Index> points;

  MaterialBatchFixture(const Material& m, Index n) : points(static_cast<size_t>(n)) {
    for (auto name : {"F", "R", "L", "stress"}) store.add_real(name, 9, "1");
    store.add_real("volume0", 1, "m^3", true, 1e-9);
    store.add_real("internal_energy", 1, "J");
    store.add_real("plastic_work", 1, "J");
    m.declare_fields(store);
    store.resize(n);
    std::iota(points.begin(), points.end(), Index{0});
    for (Index p = 0; p < n; ++p) R()[p] = F()[p] = Mat3::identity();
  }
  Mat3* F() { return store.view<Mat3>("F"); }
  Mat3* R() { return store.view<Mat3>("R"); }
  Mat3* L() { return store.view<Mat3>("L"); }
  Mat3* stress() { return store.view<Mat3>("stress"); }

  /// The batch over every point, with energy bookkeeping (as the MPM solver calls it).
  MaterialBatch batch(double dt) {
    MaterialBatch b;
    b.points = points.data();
    b.count = static_cast<Index>(points.size());
    b.F_new = F();
    b.L = L();
    b.R = R();
    b.stress = stress();
    b.store = &store;
    b.dt = dt;
    b.volume0 = store.real("volume0");
    b.internal_energy = store.real("internal_energy");
    b.plastic_energy = store.real("plastic_work");
    return b;
  }
};

}  // namespace ballista::bench
