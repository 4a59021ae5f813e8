// The contact normal of an axisymmetric run (contact.axisymmetric_normal;
// src/mpm/grid_contact.hpp): the outward vector of a field at a node, g_I = sum_p w_p grad
// N_I(x_p), is minus the gradient of what w_p carries. Inside a body of uniform density it must
// vanish, so that only surfaces set the normal. With w_p = m_p, the mass per radian rho r_p A_p, it
// does not: the mass per radian grows with r, and g_I = -(d(rho r)/dr) A-sum = about -m_I / r_I
// along r at every interior node. Within a few cells of the axis that outweighs a small body's own
// gradient (a jet point inside the rock: 1/r against the point's few-per-cell weight), the normal
// turns radial and an axial approach is read as sliding. With w_p = m_p / r_p = rho A_p ("density")
// the interior sum cancels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "deck/deck_reader.hpp"
#include "mpm/mpm_solver.hpp"
#include "run/simulation.hpp"

namespace test_contact_normal_axisymmetric {

using namespace ballista;

// A uniform cylinder (r < 10 mm, 0 < y < 10 mm) at rest and a second body away from it, so that
// the run has two velocity fields; 1 mm cells, 2 x 2 points per cell.
std::string deck(const std::string& normal, const std::string& shape = "gimp",
                 const std::string& update = "musl") {
  return std::string(R"(
simulation: {solver: mpm, dimension: axisymmetric, end_time: 1.0e-6, cfl: 0.3}
materials:
  soft: {model: neo_hookean, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
mpm: {shape_function: )") +
         shape + ", update: " + update + R"(, flip: 1.0}
grid: {lower: [0.0, -2.0e-3], upper: [16.0e-3, 20.0e-3], cell_size: 1.0e-3, boundary: {x_min: symmetry}}
bodies:
  - {name: block, material: soft, shape: {type: cylinder, center: [0, 0], axis: y, radius: 10.0e-3, length: 10.0e-3}}
  - {name: pellet, material: soft, shape: {type: cylinder, center: [0, 14.0e-3], axis: y, radius: 2.0e-3, length: 2.0e-3}}
contact: {model: friction, friction: 0, axisymmetric_normal: )" +
         normal + "}\n";
}

struct InteriorGradient {
  double worst_density = 0.0;    ///< max |g_I| h r_I / m_I over the interior nodes (dimensionless)
  double worst_ring_mass = 0.0;  ///< max |g_I| h / m_I over the same nodes (dimensionless)
  double worst_radial_vs_one_over_r = 0.0;  ///< max |g_I,r r_I / m_I + 1| over the same nodes
  double r_min = 0.0;                       ///< the innermost node radius checked, m
};

// The block's field (0) after one step from rest, at the nodes whose stencils hold only the block's
// points and are whole: r from the shape function's reach (h for hats, uGIMP and CPDI with 2 x 2
// points, whose domains end at the axis; 2 h for the cubic B-spline, whose stencil near the axis
// holds the mirrored ghost nodes) to 8 mm, y from 2 to 8 mm.
//
// Units: the node mass m_I is per radian (kg) and g_I = sum_p w_p grad N_I. With w_p = m_p
// (ring_mass) g_I is in kg/m and |g_I| h / m_I is dimensionless; with w_p = m_p / r_p (density) it
// is in kg/m^2 and |g_I| h r_I / m_I is the dimensionless measure, the same ratio a free surface
// makes about 1 in either weighting.
InteriorGradient interior_gradient(const std::string& normal, const std::string& shape = "gimp",
                                   const std::string& update = "musl") {
  const Scenario sc = parse_deck(deck(normal, shape, update), "normal.yaml");
  EXPECT_EQ(sc.contact.fields, 2);
  MpmSolver s(sc, make_materials(sc));
  s.step(1.0e-9);
  const GridData& g = s.grid();
  const double h = g.geom.h;
  InteriorGradient out;
  out.r_min = (shape == "bspline3" ? 2.0 : 1.0) * h;
  for (int i = 0; i < g.geom.nodes[0]; ++i)
    for (int j = 0; j < g.geom.nodes[1]; ++j) {
      const Vec3 x = g.geom.node_position(i, j, 0);
      if (x[0] < out.r_min - 1e-9 || x[0] > 8.0e-3 + 1e-9 || x[1] < 2.0e-3 - 1e-9 ||
          x[1] > 8.0e-3 + 1e-9)
        continue;
      const Index I = g.geom.node_index(i, j, 0);
      const double m = g.mass[I];
      const Vec3 gr = g.grad[I];
      out.worst_density = std::max(out.worst_density, norm(gr) * h * x[0] / m);
      out.worst_ring_mass = std::max(out.worst_ring_mass, norm(gr) * h / m);
      out.worst_radial_vs_one_over_r =
          std::max(out.worst_radial_vs_one_over_r, std::abs(gr[0] * x[0] / m + 1.0));
    }
  return out;
}

struct Scheme {
  const char* shape;
  const char* update;
};
// Every shape function with both updates that run contact (CPDI with USAVG is refused).
constexpr Scheme kSchemes[] = {{"gimp", "musl"},    {"gimp", "usavg"},    {"linear", "musl"},
                               {"linear", "usavg"}, {"bspline3", "musl"}, {"bspline3", "usavg"},
                               {"cpdi", "musl"}};

TEST(ContactNormalAxisymmetric, TheDensityGradientVanishesInsideAUniformBody) {
  // Round-off: g_I sums tens of terms of size rho A / h (A = h^2 / 4) that cancel in pairs by the
  // lattice's symmetry about the node; 1e-12 of the surface value is thousands of ulp of that sum
  // (measured at most 3e-15, CPDI). The points nearest the axis sit at r_p = their half-size, so
  // the weight's guard max(r_p, half) reads r_p here either way.
  for (const Scheme& sch : kSchemes) {
    const InteriorGradient d = interior_gradient("density", sch.shape, sch.update);
    std::printf(
        "density normal, %s/%s: worst |g| h r / m inside the block from r = %.0f mm: %.3e\n",
        sch.shape, sch.update, d.r_min * 1e3, d.worst_density);
    EXPECT_LT(d.worst_density, 1e-12) << sch.shape << "/" << sch.update;
  }
}

TEST(ContactNormalAxisymmetric, TheRingMassGradientIsMinusMassOverRadiusInside) {
  // The default's interior vector is -m_I / r_I e_r: on a uniform lattice the sum of the points'
  // r_p times their weights' slopes over a node is minus the node's weight sum (the linear
  // function r is reproduced exactly), so it holds to round-off (measured at most 1.5e-14, CPDI;
  // bound 1e-12 as above). Its size, m / r, is h / r of what a free surface gives (about m / h): as
  // large as a surface's at the first node off the axis, the reason the normal turns radial there.
  for (const Scheme& sch : kSchemes) {
    const InteriorGradient r = interior_gradient("ring_mass", sch.shape, sch.update);
    std::printf(
        "ring-mass normal, %s/%s: worst |g_r r / m + 1| %.3e, worst |g| h / m %.3e from r = %.0f "
        "mm\n",
        sch.shape, sch.update, r.worst_radial_vs_one_over_r, r.worst_ring_mass, r.r_min * 1e3);
    EXPECT_LT(r.worst_radial_vs_one_over_r, 1e-12) << sch.shape << "/" << sch.update;
    EXPECT_NEAR(r.worst_ring_mass, 1.0e-3 / r.r_min, 1e-12)
        << sch.shape << "/" << sch.update;  // h / r_min
  }
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
