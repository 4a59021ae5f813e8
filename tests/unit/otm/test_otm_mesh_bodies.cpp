// OTM bodies seeded at the elements of a tetrahedral mesh (bodies[].seeding: elements;
// geometry/element_seeding.hpp, OtmSolver::initial_nodes), as seed 003 §2 builds its bodies:
//  - one point per tetrahedron at its centroid with the element's volume and mass: the volumes sum
//    to the meshed box's exactly (to round-off), the centroids are the elements';
//  - the nodes are the mesh's vertices, and every point's shape functions are a partition of unity
//    with first-order consistency (sum N = 1, sum N x_a = x_p), which the LME solve can only satisfy
//    because each centroid lies inside its tetrahedron's four nodes;
//  - a lattice body beside a mesh body keeps the nodes it has alone;
//  - such a body translates rigidly (x = x0 + v t, F = I, kinetic energy unchanged);
//  - what it does not support yet is a deck error at the key that asks for it.
// Tolerances: volumes are sums of 48-384 terms (1e-15 relative), consistency residuals the LME
// tolerance 1e-12 h; the rigid motion is exact to the round-off of ~30-term sums (1e-12 relative).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "geometry/element_seeding.hpp"
#include "geometry/mesh_solid.hpp"
#include "otm/otm_solver.hpp"
#include "run/simulation.hpp"
#include "support/exodus_files.hpp"
#include "support/test_files.hpp"

namespace ballista::test_otm_mesh_bodies {
namespace {

constexpr double kH = 0.005;  // m: the mesh's hexahedra and grid.cell_size
const Vec3 kLo{{0.02, 0.03, 0.02}}, kHi{{0.04, 0.05, 0.035}};  // 4 x 4 x 3 hexahedra of 5 mm

/// A box meshed in 4 x 4 x 3 hexahedra (six tetrahedra each, by the reader).
std::string box_mesh(const test::TempDir& dir) {
  std::vector<Vec3> nodes;
  std::vector<int> hexes;
  test::box_hexes(kLo, kHi, 4, 4, 3, nodes, hexes);
  const std::string exo = (dir.path / "box.exo").string();
  test::write_exodus(exo, nodes, {{"box", "HEX8", 8, hexes}});
  return exo;
}

std::string deck(const std::string& exo, const std::string& body_extra = "", const std::string& otm = "",
                 const std::string& more_bodies = "", double cell = kH, const std::string& solver = "otm") {
  return "simulation: {solver: " + solver + ", dimension: 3d, end_time: 1.0e-4, cfl: 0.3}\n" +
         "materials:\n  rubber: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n" +
         (otm.empty() ? "" : "otm: {" + otm + "}\n") + "grid: {lower: [0.0, 0.0, 0.0], upper: [0.1, 0.1, 0.1], cell_size: " +
         std::to_string(cell) + "}\nbodies:\n  - {name: block, material: rubber, shape: {type: mesh, file: '" + exo +
         "'}, seeding: elements, velocity: [3.0, -2.0, 1.5]" + body_extra + "}\n" + more_bodies;
}

std::unique_ptr<OtmSolver> make(const std::string& yaml) {
  const Scenario sc = parse_deck(yaml, "otm_mesh_test.yaml");
  return std::make_unique<OtmSolver>(sc, make_materials(sc));
}

TEST(OtmMeshBody, PointsAtTheCentroidsWithTheElementsVolumes) {
  test::TempDir dir;
  const Scenario sc = parse_deck(deck(box_mesh(dir)), "otm_mesh_test.yaml");
  const TetMesh& mesh = element_mesh(sc.bodies[0]).mesh();
  auto s = std::make_unique<OtmSolver>(sc, make_materials(sc));
  FieldStore& pts = s->points();
  ASSERT_EQ(pts.size(), 4 * 4 * 3 * 6);
  ASSERT_EQ(static_cast<std::size_t>(pts.size()), mesh.tets.size());
  const auto* x = pts.view<Vec3>("x");
  const auto* vol = pts.real("volume");
  const auto* mass = pts.real("mass");
  const auto* id = pts.ints("id");
  double total = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    const auto& t = mesh.tets[static_cast<std::size_t>(p)];
    const Vec3 c = 0.25 * (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]] + mesh.vertices[t[3]]);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(x[p][a], c[a]) << p;
    // A hexahedron's six tetrahedra about one diagonal all hold a sixth of it.
    EXPECT_NEAR(vol[p], kH * kH * kH / 6.0, 1e-15 * kH * kH * kH) << p;
    EXPECT_DOUBLE_EQ(mass[p], 1000.0 * vol[p]);
    EXPECT_EQ(id[p], p);
    total += vol[p];
  }
  const Vec3 d = kHi - kLo;
  EXPECT_NEAR(total, d[0] * d[1] * d[2], 1e-14 * d[0] * d[1] * d[2]);
  EXPECT_NEAR(mesh_spacing(sc.bodies[0]), kH, 1e-12 * kH);  // (6 V)^(1/3) of a sixth of a cube
}

TEST(OtmMeshBody, NodesAreTheMeshVerticesAndTheShapeFunctionsConsistent) {
  test::TempDir dir;
  auto s = make(deck(box_mesh(dir)));
  const auto& nodes = s->nodes();
  ASSERT_EQ(nodes.size(), 5 * 5 * 4);
  std::set<std::tuple<double, double, double>> expected, got;
  for (int k = 0; k <= 3; ++k)
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) {
        const Vec3 v{{kLo[0] + (kHi[0] - kLo[0]) * i / 4, kLo[1] + (kHi[1] - kLo[1]) * j / 4,
                      kLo[2] + (kHi[2] - kLo[2]) * k / 3}};
        expected.insert({v[0], v[1], v[2]});
      }
  for (Index a = 0; a < nodes.size(); ++a) {
    got.insert({nodes.x[a][0], nodes.x[a][1], nodes.x[a][2]});
    EXPECT_EQ(nodes.body[a], 0);
  }
  EXPECT_EQ(got, expected);
  const auto& sup = s->supports();
  const auto* x = s->points().view<Vec3>("x");
  for (Index p = 0; p < s->points().size(); ++p) {
    double sum = 0.0;
    Vec3 xs;
    for (Index k = sup.offset[p]; k < sup.offset[p + 1]; ++k) {
      sum += sup.N[k];
      xs += sup.N[k] * nodes.x[sup.node[k]];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << p;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(xs[a], x[p][a], 1e-12 * kH) << p;
  }
}

TEST(OtmMeshBody, ALatticeBodyBesideItKeepsItsOwnNodes) {
  test::TempDir dir;
  const std::string exo = box_mesh(dir);
  const std::string lattice_body =
      "  - {name: cube, material: rubber, shape: {type: box, lower: [0.06, 0.06, 0.06], upper: [0.08, 0.075, 0.08]}}\n";
  auto both = make(deck(exo, "", "", lattice_body));
  // The cube alone on the same grid.
  const std::string alone = "simulation: {solver: otm, dimension: 3d, end_time: 1.0e-4, cfl: 0.3}\n"
                            "materials:\n  rubber: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e7, "
                            "poisson_ratio: 0.3}\ngrid: {lower: [0.0, 0.0, 0.0], upper: [0.1, 0.1, 0.1], cell_size: 0.005}\n"
                            "bodies:\n" + lattice_body;
  auto cube = make(alone);
  const auto& nb = both->nodes();
  const auto& nc = cube->nodes();
  Index lattice_nodes = 0;
  for (Index a = 0; a < nb.size(); ++a) lattice_nodes += nb.body[a] == 1;
  ASSERT_EQ(lattice_nodes, nc.size());
  ASSERT_EQ(nb.size(), nc.size() + 5 * 5 * 4);
  // The lattice body's nodes come first, in the order they have alone.
  for (Index a = 0; a < nc.size(); ++a)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(nb.x[a][d], nc.x[a][d]) << a;
}

TEST(OtmMeshBody, TranslatesRigidly) {
  test::TempDir dir;
  auto s = make(deck(box_mesh(dir)));
  const Vec3 v0{{3.0, -2.0, 1.5}};
  const double ke0 = s->energies().kinetic;
  FieldStore& pts = s->points();
  std::vector<Vec3> x0(pts.view<Vec3>("x"), pts.view<Vec3>("x") + pts.size());
  double t = 0.0;
  for (int k = 0; k < 20; ++k) {
    const double dt = s->stable_dt();
    s->step(dt);
    t += dt;
  }
  const auto* x = pts.view<Vec3>("x");
  const auto* F = pts.view<Mat3>("F");
  const auto* v = pts.view<Vec3>("v");
  for (Index p = 0; p < pts.size(); ++p) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(x[p][a], x0[static_cast<std::size_t>(p)][a] + v0[a] * t, 1e-12 * 0.1) << p;
      EXPECT_NEAR(v[p][a], v0[a], 1e-12 * 3.0) << p;
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(F[p](a, b), a == b ? 1.0 : 0.0, 1e-12) << p;
    }
  }
  EXPECT_NEAR(s->energies().kinetic, ke0, 1e-12 * ke0);
}

/// parse + build, expecting a DeckError whose message contains every one of `words`.
void expect_refused(const std::string& yaml, const std::vector<std::string>& words) {
  try {
    make(yaml);
    FAIL() << "accepted:\n" << yaml;
  } catch (const DeckError& e) {
    for (const std::string& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
  }
}

TEST(OtmMeshBody, WhatItDoesNotSupportIsADeckErrorAtItsKey) {
  test::TempDir dir;
  const std::string exo = box_mesh(dir);
  // Seeding at elements needs a mesh shape and a solver whose nodes are the mesh's vertices.
  expect_refused("simulation: {solver: otm, dimension: 3d, end_time: 1.0e-4}\n"
                 "materials:\n  rubber: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n"
                 "grid: {lower: [0, 0, 0], upper: [0.1, 0.1, 0.1], cell_size: 0.005}\n"
                 "bodies:\n  - {name: b, material: rubber, shape: {type: box, lower: [0.02, 0.02, 0.02], "
                 "upper: [0.04, 0.04, 0.04]}, seeding: elements}\n",
                 {"bodies.0.seeding", "is a box"});
  expect_refused(deck(exo, "", "", "", kH, "mpm"), {"bodies.0.seeding", "otm"});
  expect_refused(deck(exo, ", particles_per_cell: 3"), {"bodies.0.particles_per_cell"});
  expect_refused(deck(exo, ", cutouts: [{type: sphere, center: [0.03, 0.04, 0.03], radius: 0.002}]"),
                 {"bodies.0.cutouts"});
  // What the OTM solver does not do with such a body yet.
  expect_refused(deck(exo, "", "adaptivity: true"), {"otm.adaptivity"});
  expect_refused(deck(exo, "", "nodes: shared"), {"otm.nodes"});
  // The LME locality assumes grid.cell_size is the nodal spacing: a mesh twice as fine is refused.
  expect_refused(deck(exo, "", "", "", 2.0 * kH), {"bodies.0.seeding", "factor 1.5"});
  // A mesh reaching out of the grid box.
  std::vector<Vec3> nodes;
  std::vector<int> hexes;
  test::box_hexes({{0.09, 0.03, 0.02}}, {{0.11, 0.05, 0.035}}, 4, 4, 3, nodes, hexes);
  const std::string out = (dir.path / "out.exo").string();
  test::write_exodus(out, nodes, {{"box", "HEX8", 8, hexes}});
  expect_refused(deck(out), {"body 'block'", "vertices of its mesh lie outside the grid box"});
  // A pressure is applied to points found on a lattice.
  expect_refused(deck(exo) + "loads:\n  - {type: pressure, body: block, surface: outer, pressure: 1.0e5}\n",
                 {"body", "seeded at its mesh's elements"});
}

}  // namespace
}  // namespace ballista::test_otm_mesh_bodies
