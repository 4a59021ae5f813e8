// Thread-count independence: the same deck run with 1 and 2 OpenMP threads must give bitwise
// identical particle states (src/core/parallel.hpp: loops write disjoint data, the P2G scatter is
// coloured by slabs so every node sums its contributions in point order, and reductions combine
// fixed-size chunks in chunk order). Covers plane strain + neo-Hookean + MUSL, axisymmetric and
// 3D J2 plasticity against a wall. Each case has more points and grid nodes than
// kParallelThreshold, so the 2-thread run really takes the parallel paths.
#include <algorithm>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/parallel.hpp"
#include "verification/verification_support.hpp"

namespace test_determinism {

using namespace ballista;
using namespace ballista::verification;

namespace {

struct Snapshot {
  std::vector<std::int64_t> id;
  std::vector<std::vector<double>> fields;  // per compared field, points ordered by id
  EnergyTotals energy;
  long steps = 0;
  double time = 0.0;
  Index points = 0;
  Index nodes = 0;
};

const std::vector<std::string> kCompared = {"x", "v", "F", "stress", "volume", "internal_energy"};

Snapshot run_with_threads(const Scenario& sc, int threads) {
  set_threads(threads);
  auto solver = make_solver(sc);
  advance(*solver, sc.simulation.end_time, sc.output.interval);
  const FieldStore& pts = solver->points();
  Snapshot s;
  s.points = pts.size();
  s.steps = solver->steps();
  s.time = solver->time();
  s.energy = solver->energies();
  const std::int64_t* id = pts.ints("id");
  std::vector<Index> order(pts.size());
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return id[a] < id[b]; });
  for (Index p : order) s.id.push_back(id[p]);
  std::vector<std::string> names = kCompared;
  if (pts.has("eqps")) names.push_back("eqps");
  for (const auto& name : names) {
    const int nc = pts.info(name).ncomp;
    const double* f = pts.real(name);
    std::vector<double> out;
    out.reserve(static_cast<size_t>(pts.size()) * nc);
    for (Index p : order) out.insert(out.end(), f + p * nc, f + (p + 1) * nc);
    s.fields.push_back(std::move(out));
  }
  return s;
}

void expect_bitwise_equal(const Scenario& sc, const char* what) {
  const int saved = max_threads();
  const Snapshot one = run_with_threads(sc, 1);
  const Snapshot two = run_with_threads(sc, 2);
  set_threads(saved);
  std::printf("%s: %lld points, %ld steps, t = %.6g s\n", what, static_cast<long long>(one.points),
              one.steps, one.time);
  // Not vacuous: below kParallelThreshold points every loop would run serially.
  ASSERT_GT(one.points, kParallelThreshold);
  ASSERT_EQ(one.steps, two.steps);
  ASSERT_EQ(one.time, two.time);
  ASSERT_EQ(one.id, two.id);
  ASSERT_EQ(one.fields.size(), two.fields.size());
  for (size_t k = 0; k < one.fields.size(); ++k) {
    ASSERT_EQ(one.fields[k].size(), two.fields[k].size());
    // Bitwise (memcmp), not ==: also distinguishes -0.0 from 0.0 and catches NaN.
    const bool same = std::memcmp(one.fields[k].data(), two.fields[k].data(),
                                  one.fields[k].size() * sizeof(double)) == 0;
    size_t first = 0;
    if (!same)
      while (first < one.fields[k].size() &&
             std::memcmp(&one.fields[k][first], &two.fields[k][first], sizeof(double)) == 0)
        ++first;
    EXPECT_TRUE(same) << what << ": field #" << k << " differs first at component " << first
                      << ": " << (same ? 0.0 : one.fields[k][first]) << " vs "
                      << (same ? 0.0 : two.fields[k][first]);
  }
  // Every term bitwise; the per-body arrays by their values (the struct holds their addresses).
  auto terms = [](const EnergyTotals& e) {
    std::vector<double> t{e.kinetic, e.internal, e.plastic, e.eroded, e.external, e.mass, e.momentum[0],
                          e.momentum[1], e.momentum[2], e.removed_mass, e.removed_energy, e.removed_momentum[0],
                          e.removed_momentum[1], e.removed_momentum[2], e.inserted_energy, e.chemical, e.damping,
                          e.contact, e.friction, e.transfer, e.boundary, e.viscous};
    for (const auto* v : {&e.removed_points_by_body, &e.removed_mass_by_body, &e.removed_energy_by_body,
                          &e.seeded_mass_by_body})
      t.insert(t.end(), v->begin(), v->end());
    return t;
  };
  const std::vector<double> e1 = terms(one.energy), e2 = terms(two.energy);
  ASSERT_EQ(e1.size(), e2.size());
  EXPECT_EQ(std::memcmp(e1.data(), e2.data(), e1.size() * sizeof(double)), 0) << what << ": energy totals";
}

}  // namespace

TEST(Determinism, ElasticDisksPlaneStrainMusl) {
  // The disks at twice the deck's resolution (~6.4k points, 7.6k nodes), moved closer so they are
  // in contact before the end (contact from ~0.6 s), CFL 0.3 to keep it short (~250 steps).
  const Scenario sc = load_example(
      "elastic_disks.yaml",
      {"grid.cell_size=0.0125", "simulation.end_time=0.8", "simulation.cfl=0.3",
       "bodies.0.shape={type: cylinder, center: [0.3, 0.3, 0], axis: z, radius: 0.2}",
       "bodies.1.shape={type: cylinder, center: [0.7, 0.7, 0], axis: z, radius: 0.2}"});
  expect_bitwise_equal(sc, "elastic disks");
}

TEST(Determinism, TaylorBarAxisymmetricJ2) {
  // The deck's full resolution (0.2 mm, ~10k points) for the first 4 us of the impact (~330
  // steps; plastic flow starts at once at the impact face).
  const Scenario sc = load_example("taylor_bar_mpm.yaml", {"simulation.end_time=4e-6"});
  expect_bitwise_equal(sc, "axisymmetric Taylor bar");
}

TEST(Determinism, TaylorBar3dQuarterJ2) {
  // Quarter bar at 0.6 mm (~9.6k points) for the first 10 us: 3D, J2, wall and symmetry planes.
  const Scenario sc = load_example("taylor_bar_mpm_3d.yaml", {"grid.cell_size=0.6e-3", "simulation.end_time=10e-6"});
  expect_bitwise_equal(sc, "3D quarter Taylor bar");
}

}  // namespace test_determinism
