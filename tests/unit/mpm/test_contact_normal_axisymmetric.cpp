// The contact normal of an axisymmetric run (contact.axisymmetric_normal; src/mpm/grid_contact.hpp):
// the outward vector of a field at a node, g_I = sum_p w_p grad N_I(x_p), is minus the gradient
// of what w_p carries. Inside a body of uniform density it must vanish, so that only surfaces set
// the normal. With w_p = m_p, the mass per radian rho r_p A_p, it does not: the mass per radian
// grows with r, and g_I = -(d(rho r)/dr) A-sum = about -m_I / r_I along r at every interior node.
// Within a few cells of the axis that outweighs a small body's own gradient (a jet point inside the
// rock: 1/r against the point's few-per-cell weight), the normal turns radial and an axial approach
// is read as sliding. With w_p = m_p / r_p = rho A_p ("density") the interior sum cancels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "deck/deck_reader.hpp"
#include "mpm/mpm_solver.hpp"
#include "run/simulation.hpp"

namespace test_contact_normal_axisymmetric {

using namespace ballista;

// A uniform cylinder (r < 10 mm, 0 < y < 10 mm) at rest and a second body away from it, so that
// the run has two velocity fields; 1 mm cells, uGIMP, 2 x 2 points per cell.
std::string deck(const std::string& normal) {
  return std::string(R"(
simulation: {solver: mpm, dimension: axisymmetric, end_time: 1.0e-6, cfl: 0.3}
materials:
  soft: {model: neo_hookean, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
mpm: {shape_function: gimp, update: musl, flip: 1.0}
grid: {lower: [0.0, -2.0e-3], upper: [16.0e-3, 20.0e-3], cell_size: 1.0e-3, boundary: {x_min: symmetry}}
bodies:
  - {name: block, material: soft, shape: {type: cylinder, center: [0, 0], axis: y, radius: 10.0e-3, length: 10.0e-3}}
  - {name: pellet, material: soft, shape: {type: cylinder, center: [0, 14.0e-3], axis: y, radius: 2.0e-3, length: 2.0e-3}}
contact: {model: friction, friction: 0, axisymmetric_normal: )") +
         normal + "}\n";
}

struct InteriorGradient {
  double worst_over_mass_per_h = 0.0;  ///< max |g_I| h / m_I over the interior nodes
  double worst_radial_vs_one_over_r = 0.0;  ///< max |g_I,r r_I / m_I + 1| over the same nodes
};

// The block's field (0) after one step from rest: nodes from 2 to 8 mm in r and y, whose stencils
// hold only the block's points.
InteriorGradient interior_gradient(const std::string& normal) {
  const Scenario sc = parse_deck(deck(normal), "normal.yaml");
  EXPECT_EQ(sc.contact.fields, 2);
  MpmSolver s(sc, make_materials(sc));
  s.step(1.0e-9);
  const GridData& g = s.grid();
  const double h = g.geom.h;
  InteriorGradient out;
  for (int i = 0; i < g.geom.nodes[0]; ++i)
    for (int j = 0; j < g.geom.nodes[1]; ++j) {
      const Vec3 x = g.geom.node_position(i, j, 0);
      if (x[0] < 2.0e-3 - 1e-9 || x[0] > 8.0e-3 + 1e-9 || x[1] < 2.0e-3 - 1e-9 || x[1] > 8.0e-3 + 1e-9) continue;
      const Index I = g.geom.node_index(i, j, 0);
      const double m = g.mass[I];
      const Vec3 gr = g.grad[I];
      out.worst_over_mass_per_h = std::max(out.worst_over_mass_per_h, norm(gr) * h / m);
      out.worst_radial_vs_one_over_r = std::max(out.worst_radial_vs_one_over_r, std::abs(gr[0] * x[0] / m + 1.0));
    }
  return out;
}

TEST(ContactNormalAxisymmetric, TheDensityGradientVanishesInsideAUniformBody) {
  // Round-off: g_I sums 16 terms of size rho A / h (A = h^2 / 4) that cancel in pairs by the
  // lattice's symmetry about the node; 1e-12 of m_I / h is a few hundred ulp of that sum.
  const InteriorGradient d = interior_gradient("density");
  std::printf("density normal: worst |g| h / m inside the block %.3e\n", d.worst_over_mass_per_h);
  EXPECT_LT(d.worst_over_mass_per_h, 1e-12);
}

TEST(ContactNormalAxisymmetric, TheRingMassGradientIsMinusMassOverRadiusInside) {
  // The default's interior vector is -m_I / r_I e_r: on a uniform lattice the sum of the points'
  // r_p times their weights' slopes over a node is minus the node's weight sum (the linear
  // function r is reproduced exactly), so it holds to round-off (measured 2e-15; bound 1e-12 as
  // above). At r = 2 h its size, m / (2 h), is half of what a free surface gives (about m / h):
  // the reason the normal turns radial near the axis.
  const InteriorGradient r = interior_gradient("ring_mass");
  std::printf("ring-mass normal: worst |g_r r / m + 1| inside the block %.3e, worst |g| h / m %.3e\n",
              r.worst_radial_vs_one_over_r, r.worst_over_mass_per_h);
  EXPECT_LT(r.worst_radial_vs_one_over_r, 1e-12);
  EXPECT_NEAR(r.worst_over_mass_per_h, 0.5, 1e-12);  // at r = 2 mm = 2 h
}

TEST(ContactNormalAxisymmetric, TheKeyIsRefusedOutsideAxisymmetricRuns) {
  std::string d = deck("density");
  d.replace(d.find("dimension: axisymmetric"), 23, "dimension: plane_strain");
  try {
    parse_deck(d, "normal.yaml");
    FAIL() << "expected a deck error";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "contact.axisymmetric_normal");
  }
}

}  // namespace test_contact_normal_axisymmetric
