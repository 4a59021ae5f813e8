// OTM verification of a body seeded at the elements of a tetrahedral mesh (bodies[].seeding:
// elements; its nodes are the mesh's vertices): an elastic steel column, 4 x 50 x 4 mm, between
// symmetry planes on its four sides (uniaxial strain) hits a rigid wall at v = 10 m/s.
// One-dimensional wave theory (Graff, Wave Motion in Elastic Solids, §2.1, with the P-wave modulus
// M = K + 4G/3 of uniaxial strain): the compression wave runs up the column and back in 2L/c_p,
// c_p = sqrt(M/rho), and the column leaves the wall at the speed it came with; nothing is lost to
// lateral motion, which the symmetry planes forbid. Checks:
//  - the contact lasts 2L/c_p within 5 % (first to last step with a wall force; the front is
//    smeared over a few elements, 2-3 % of the 50-element column);
//  - the column rebounds at 0.95-1.0 v (what the dispersion of the discrete wave leaves in
//    vibration; 1D theory is the upper bound);
//  - the energy balance closes within 1 % of the kinetic energy (the wall's work booked).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "deck/deck_reader.hpp"
#include "otm/otm_solver.hpp"
#include "run/simulation.hpp"
#include "support/exodus_files.hpp"
#include "support/test_files.hpp"

namespace ballista::test_otm_mesh_column {
namespace {

constexpr double kRho = 7850.0, kE = 200.0e9, kNu = 0.3, kL = 0.05, kV = 10.0, kEnd = 2.5e-5;

TEST(OtmMeshColumn, AnElasticColumnFromAMeshReboundsAfterTwoWaveTransits) {
  test::TempDir dir;
  std::vector<Vec3> nodes;
  std::vector<int> hexes;
  test::box_hexes({{0, 0, 0}}, {{0.004, kL, 0.004}}, 4, 50, 4, nodes, hexes);  // 1 mm hexahedra
  const std::string exo = (dir.path / "column.exo").string();
  test::write_exodus(exo, nodes, {{"column", "HEX8", 8, hexes}});
  const std::string yaml = R"(
simulation: {solver: otm, dimension: 3d, end_time: 2.5e-5, cfl: 0.9}
materials:
  steel: {model: linear_elastic, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.3}
grid:
  lower: [0, 0, 0]
  upper: [0.004, 0.06, 0.004]
  cell_size: 1.0e-3
  boundary: {x_min: symmetry, x_max: symmetry, z_min: symmetry, z_max: symmetry, y_min: wall}
bodies:
  - {name: column, material: steel, shape: {type: mesh, file: ')" + exo + R"('}, seeding: elements,
     velocity: [0, -10.0, 0]}
)";
  const Scenario sc = parse_deck(yaml, "otm_mesh_column.yaml");
  OtmSolver s(sc, make_materials(sc));
  ASSERT_EQ(s.points().size(), 4 * 50 * 4 * 6);
  const EnergyTotals e0 = s.energies();
  double first = -1.0, last = -1.0;
  while (s.time() < kEnd) {
    const double t0 = s.time();
    s.step(s.stable_dt());
    if (std::abs(s.history_values()[0]) > 0.0) {
      if (first < 0.0) first = t0;
      last = s.time();
    }
  }
  const double M = kE * (1.0 - kNu) / ((1.0 + kNu) * (1.0 - 2.0 * kNu));
  const double t_contact = 2.0 * kL / std::sqrt(M / kRho);
  const EnergyTotals e = s.energies();
  const double residual = (e.total() - e0.total()) / e0.kinetic;
  const double rebound = e.momentum[1] / e.mass / kV;
  std::printf("contact %.4g s (2L/c_p %.4g s, ratio %.4f), rebound %.4f v, residual %.2e\n", last - first, t_contact,
              (last - first) / t_contact, rebound, residual);
  EXPECT_NEAR(last - first, t_contact, 0.05 * t_contact);
  EXPECT_GT(rebound, 0.95);
  EXPECT_LE(rebound, 1.0);
  EXPECT_LT(std::abs(residual), 0.01);
}

}  // namespace
}  // namespace ballista::test_otm_mesh_column
