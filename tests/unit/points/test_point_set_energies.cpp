// PointSet::energies against sums done here: kinetic energy, internal energy, mass, momentum and the
// internal energy held by failed (eroded) points. A regression test: GCC 12.2 with -O3
// -march=native vectorised the conditional eroded-energy sum of energies() into a copy of the mass
// sum (every summary reported eroded_internal_energy = mass); the build now disables the SLP
// vectoriser (CMakeLists.txt). Sums of a few hundred terms: 1e-12 relative is round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "deck/deck_reader.hpp"
#include "materials/failure.hpp"
#include "points/point_set.hpp"
#include "run/simulation.hpp"

namespace ballista::test_point_set_energies {
namespace {

Scenario deck(bool with_failure) {
  std::string yaml = R"(
simulation: {solver: mpm, dimension: 3d, end_time: 1.0e-6}
materials:
  steel:
    model: j2_plasticity
    density: 7850
    youngs_modulus: 200.0e9
    poisson_ratio: 0.3
    yield_stress: 500.0e6
    hardening_modulus: 1.0e9
)";
  if (with_failure)
    yaml += "    failure: {criterion: johnson_cook_damage, erosion: zero_stress, d1: 1.0, d2: 0, d3: 0, d4: 0, d5: 0}\n";
  yaml += R"(
grid: {lower: [0, 0, 0], upper: [4.0e-3, 4.0e-3, 4.0e-3], cell_size: 1.0e-3}
bodies:
  - {name: block, material: steel, shape: {type: box, lower: [1.0e-3, 1.0e-3, 1.0e-3], upper: [3.0e-3, 3.0e-3, 3.0e-3]}, velocity: [3.0, -4.0, 12.0]}
)";
  return parse_deck(yaml, "energies_test.yaml");
}

void check(bool with_failure) {
  const Scenario sc = deck(with_failure);
  PointSet pts(sc, make_materials(sc), SeedLattice{sc.grid, 0}, 0.0, "");
  FieldStore& s = pts.store();
  const Index n = s.size();
  ASSERT_GT(n, 8);
  auto* eint = s.real("internal_energy");
  double* failed = with_failure ? s.real(kFailedField) : nullptr;
  double mass = 0.0, ke = 0.0, e_all = 0.0, e_failed = 0.0, py = 0.0;
  const auto* m = s.real("mass");
  const auto* v = s.view<Vec3>("v");
  for (Index p = 0; p < n; ++p) {
    eint[p] = 1.0 + 0.5 * static_cast<double>(p);
    if (failed) failed[p] = (p % 3 == 0) ? 1.0 : 0.0;
    mass += m[p];
    ke += 0.5 * m[p] * dot(v[p], v[p]);
    py += m[p] * v[p][1];
    e_all += eint[p];
    if (failed && failed[p] > 0.0) e_failed += eint[p];
  }
  const EnergyTotals e = pts.energies(1.0, 0.0);
  EXPECT_NEAR(e.mass, mass, 1e-12 * mass);
  EXPECT_NEAR(e.kinetic, ke, 1e-12 * ke);
  EXPECT_NEAR(e.internal, e_all, 1e-12 * e_all);
  EXPECT_NEAR(e.momentum[1], py, 1e-12 * std::abs(py));
  EXPECT_NEAR(e.eroded, e_failed, 1e-12 * e_all) << "with_failure " << with_failure;
}

TEST(PointSetEnergies, SumsMatchWithoutFailedPoints) { check(false); }
TEST(PointSetEnergies, ErodedEnergyIsThatOfTheFailedPoints) { check(true); }

}  // namespace
}  // namespace ballista::test_point_set_energies
