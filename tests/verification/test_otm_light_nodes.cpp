// Light nodes in OTM (OtmSolver::light_nodes): the copper Taylor bar of
// examples/taylor_bar_otm_3d_mesh.yaml seeded on the lattice (a quarter bar, 0.8 mm, 2 points per
// cell) to 20 us. As the foot spreads, lattice nodes of the staircase's corners are left outside the
// body, reached only by the tails of the points' shape functions. Their mass and force both scale
// with those tails, so their acceleration does not: integrated like the other nodes, one of them
// moved at 2,103 m/s at 20 us (9 times the impact speed), and at 0.4 mm such a node, carried back
// into the bar at 9.8 km/s, inverted a point at the wall (docs/validation.md, "3D from a
// tetrahedral mesh"). Checks:
//  - light nodes occurred and were carried (solver result light_node_steps > 0);
//  - no node that carries mass moves faster than 1.5 times the impact speed. The bar only
//    decelerates against the wall (its fastest nodes inside the body move at 223 m/s at 20 us), but
//    nodes just outside its surface, above the light share (1e-3 to 1e-2 of a point's mass), are
//    still only loosely held and overshoot: measured 315 m/s (1.39 times the impact speed); the
//    bound is there to catch the tails' km/s drift, not that overshoot (docs/validation.md);
//  - the energy balance, with the carried nodes' kinetic-energy change booked as transfer work,
//    closes to 1 % of the initial kinetic energy (measured 0.23 %, the same with the carry off),
//    and the carried nodes' share of it is below 1e-4 of the initial kinetic energy (measured
//    1.1e-5).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "deck/deck_reader.hpp"
#include "otm/otm_solver.hpp"
#include "run/simulation.hpp"

namespace ballista::test_otm_light_nodes {
namespace {

constexpr double kImpactSpeed = 227.0;  // m/s

const char* kDeck = R"(
simulation: {solver: otm, dimension: 3d, end_time: 2.0e-5, cfl: 0.9}
materials:
  copper: {model: j2_plasticity, density: 8930, youngs_modulus: 117.0e9, poisson_ratio: 0.35,
           yield_stress: 400.0e6, hardening_modulus: 100.0e6}
otm: {gamma: 1.8, wall_model: constraint}
grid: {lower: [0, 0, 0], upper: [10.0e-3, 34.0e-3, 10.0e-3], cell_size: 0.8e-3,
       boundary: {x_min: symmetry, z_min: symmetry, y_min: wall}}
bodies:
  - {name: bar, material: copper, shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 3.2e-3, length: 32.4e-3},
     particles_per_cell: 2, velocity: [0, -227.0, 0]}
)";

TEST(OtmLightNodes, TheLatticeBarsOutsideNodesMoveWithTheMaterial) {
  const Scenario sc = parse_deck(kDeck, "otm_light_nodes.yaml");
  OtmSolver s(sc, make_materials(sc));
  const EnergyTotals e0 = s.energies();
  const double end = sc.simulation.end_time;
  while (s.time() < end) s.step(std::min(s.stable_dt(), end - s.time() + 1e-12));
  double carried = 0.0;
  for (const auto& [k, v] : s.result_values())
    if (k == "light_node_steps") carried = v;
  EXPECT_GT(carried, 0.0);
  const otm::NodeCloud& nodes = s.nodes();
  double fastest = 0.0;
  for (Index a = 0; a < nodes.size(); ++a)
    if (nodes.mass[a] > 0.0) fastest = std::max(fastest, norm(nodes.v[a]));
  EXPECT_LT(fastest, 1.5 * kImpactSpeed);
  const EnergyTotals e = s.energies();
  const double residual = (e.total() - e0.total()) / e0.kinetic;
  EXPECT_LT(std::abs(residual), 0.01);
  EXPECT_LT(std::abs(e.transfer), 1e-4 * e0.kinetic);
  std::printf("lattice bar, 0.8 mm, 20 us: %g light node-steps, fastest node %.1f m/s, residual %.5f, transfer %.2e "
              "of the initial kinetic energy\n",
              carried, fastest, residual, e.transfer / e0.kinetic);
}

}  // namespace
}  // namespace ballista::test_otm_light_nodes
