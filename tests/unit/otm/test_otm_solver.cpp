// OtmSolver (src/otm/otm_solver.hpp) against closed forms and conservation laws:
//  - a free elastic block translates rigidly in 3D, plane strain and axisymmetric (x = x0 + v t,
//    F = I, no stress, kinetic energy and momentum unchanged): the shape functions reproduce a
//    uniform motion exactly (partition of unity and first-order consistency, lme_shape.hpp);
//  - the nodes are the vertices of the cells holding points, and every point's shape functions
//    satisfy sum N = 1 and sum N x_a = x_p;
//  - a block under a uniform body force follows the solver's discrete trajectory exactly;
//  - results are bitwise independent of the thread count.
// Round-off: sums of ~15-90 shape-function terms of nodes ~1e-2 m away (1e-16 relative each), the
// LME tolerance 1e-12 h on the consistency residual; 1e-12 relative (or 1e-13 m) bounds sit above.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "deck/deck_reader.hpp"
#include "otm/otm_solver.hpp"
#include "run/simulation.hpp"

namespace ballista::test_otm_solver {
namespace {

std::string deck(const std::string& dim, const std::string& velocity, const std::string& extra = "") {
  const bool axi = dim == "axisymmetric";
  const bool two = dim != "3d";
  std::string lower = two ? "[0.0, 0.0]" : "[0.0, 0.0, 0.0]";
  std::string upper = two ? "[0.1, 0.1]" : "[0.1, 0.1, 0.1]";
  std::string shape = axi ? "{type: cylinder, center: [0, 0.03, 0], axis: y, radius: 0.02, length: 0.03}"
                          : (two ? "{type: box, lower: [0.03, 0.03], upper: [0.06, 0.05]}"
                                 : "{type: box, lower: [0.03, 0.03, 0.03], upper: [0.05, 0.06, 0.05]}");
  return "simulation: {solver: otm, dimension: " + dim + ", end_time: 1.0e-4, cfl: 0.3}\n" +
         "materials:\n  rubber: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n" +
         "grid: {lower: " + lower + ", upper: " + upper + ", cell_size: 0.005" + (axi ? ", boundary: {x_min: symmetry}" : "") +
         "}\n" + "bodies:\n  - {name: block, material: rubber, shape: " + shape + ", velocity: " + velocity + "}\n" + extra;
}

std::unique_ptr<OtmSolver> make(const std::string& yaml) {
  const Scenario sc = parse_deck(yaml, "otm_test.yaml");
  return std::make_unique<OtmSolver>(sc, make_materials(sc));
}

class OtmFreeBlock : public ::testing::TestWithParam<std::string> {};

TEST_P(OtmFreeBlock, TranslatesRigidly) {
  const std::string dim = GetParam();
  const Vec3 v0 = dim == "3d" ? Vec3{{3.0, -2.0, 1.5}} : (dim == "plane_strain" ? Vec3{{3.0, -2.0, 0.0}} : Vec3{{0.0, -2.0, 0.0}});
  const std::string vel = "[" + std::to_string(v0[0]) + ", " + std::to_string(v0[1]) + ", " + std::to_string(v0[2]) + "]";
  auto s = make(deck(dim, vel));
  const EnergyTotals e0 = s->energies();
  FieldStore& pts = s->points();
  const Index n = pts.size();
  // The shape functions at t = 0: partition of unity and consistency at every point.
  const auto& sup = s->supports();
  const auto* x = pts.view<Vec3>("x");
  for (Index p = 0; p < n; ++p) {
    double sum = 0.0;
    Vec3 xs;
    for (Index k = sup.offset[p]; k < sup.offset[p + 1]; ++k) {
      sum += sup.N[k];
      xs += sup.N[k] * s->nodes().x[sup.node[k]];
    }
    ASSERT_NEAR(sum, 1.0, 1e-13);
    for (int a = 0; a < 3; ++a) ASSERT_NEAR(xs[a], x[p][a], 1e-13);
  }
  double t = 0.0;
  for (int k = 0; k < 25; ++k) {
    const double dt = s->stable_dt();
    s->step(dt);
    t += dt;
  }
  const auto* x0 = pts.view<Vec3>("x0");
  const auto* F = pts.view<Mat3>("F");
  const auto* stress = pts.view<Mat3>("stress");
  for (Index p = 0; p < n; ++p) {
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(x[p][a], x0[p][a] + v0[a] * t, 1e-13) << "point " << p;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(F[p](i, j), i == j ? 1.0 : 0.0, 1e-11);
    EXPECT_LT(frobenius(stress[p]), 1e-11 * 1.0e7);
  }
  const EnergyTotals e1 = s->energies();
  EXPECT_NEAR(e1.kinetic, e0.kinetic, 1e-12 * e0.kinetic);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(e1.momentum[a], e0.momentum[a], 1e-12 * norm(e0.momentum) + 1e-300);
}

INSTANTIATE_TEST_SUITE_P(Dims, OtmFreeBlock, ::testing::Values("3d", "plane_strain", "axisymmetric"));

// A body with a later activation (activation_time) arrives with nodes of its own at the vertices of
// the cells holding its points, their velocities projected from the points: from its arrival it
// translates rigidly, x = x0 + v (t - t_arrival), while the body present from the start stays at
// rest; its kinetic energy is booked as inserted and its momentum counts as initial.
TEST(OtmActivation, ALaterBodyArrivesWithItsNodesAndTranslatesRigidly) {
  const std::string yaml = deck("plane_strain", "[0, 0, 0]",
                                "  - {name: late, material: rubber, shape: {type: box, lower: [0.065, 0.03], upper: "
                                "[0.08, 0.045]}, velocity: [2.0, 1.0, 0], activation_time: 2.0e-5}\n");
  auto s = make(yaml);
  FieldStore& pts = s->points();
  const Index n_block = pts.size(), nodes_block = s->nodes().size();
  double t = 0.0, arrival = -1.0;
  for (int k = 0; k < 40; ++k) {
    const double dt = s->stable_dt();
    if (arrival < 0.0 && pts.size() > n_block) arrival = t;
    s->step(dt);
    t += dt;
  }
  ASSERT_GE(arrival, 2.0e-5);
  ASSERT_GT(pts.size(), n_block);
  // The late box (3 x 3 cells of 5 mm, its corner on the lattice) brings its own 4 x 4 nodes.
  EXPECT_EQ(s->nodes().size(), nodes_block + 16);
  const auto* x = pts.view<Vec3>("x");
  const auto* x0 = pts.view<Vec3>("x0");
  const auto* body = pts.ints("body");
  const Vec3 v{{2.0, 1.0, 0.0}};
  double kinetic = 0.0;
  const auto* m = pts.real("mass");
  for (Index p = 0; p < pts.size(); ++p) {
    const double move = body[p] == 1 ? t - arrival : 0.0;
    for (int a = 0; a < 2; ++a) EXPECT_NEAR(x[p][a], x0[p][a] + (body[p] == 1 ? v[a] : 0.0) * move, 1e-13) << p;
    if (body[p] == 1) kinetic += 0.5 * m[p] * dot(v, v);
  }
  const EnergyTotals e = s->energies();
  EXPECT_NEAR(e.kinetic, kinetic, 1e-12 * kinetic);
  EXPECT_NEAR(e.inserted_energy, kinetic, 1e-12 * kinetic);
  for (const auto& [name, value] : s->result_values())
    if (name.rfind("momentum_change", 0) == 0) EXPECT_NEAR(value, 0.0, 1e-12 * kinetic) << name;
}

// simulation.on_particle_exit: delete: a block translating through the box's free face loses the
// points that cross it, with their mass and kinetic energy booked as removed (exactly the nodes'
// for a uniform motion), the nodes no point supports any more go, and the rest keeps translating
// rigidly.
TEST(OtmExit, PointsLeavingTheBoxAreDeletedWithTheirBooking) {
  std::string yaml = deck("plane_strain", "[100.0, 0, 0]", "");
  yaml.replace(yaml.find("end_time: 1.0e-4"), 16, "end_time: 1.0e-3, on_particle_exit: delete");
  auto s = make(yaml);
  FieldStore& pts = s->points();
  const EnergyTotals e0 = s->energies();
  const Index n0 = pts.size(), nn0 = s->nodes().size();
  double t = 0.0;
  // The block (x from 30 to 60 mm) moves 100 m/s towards the face x = 100 mm: at 0.55 ms its
  // front half has crossed.
  while (t < 5.5e-4) {
    const double dt = s->stable_dt();
    s->step(dt);
    t += dt;
  }
  ASSERT_LT(pts.size(), n0);
  ASSERT_GT(pts.size(), 0);
  EXPECT_LT(s->nodes().size(), nn0);
  const auto* x = pts.view<Vec3>("x");
  const auto* x0 = pts.view<Vec3>("x0");
  for (Index p = 0; p < pts.size(); ++p) {
    EXPECT_LE(x[p][0], 0.1);
    EXPECT_NEAR(x[p][0], x0[p][0] + 100.0 * t, 1e-12);
  }
  const EnergyTotals e = s->energies();
  EXPECT_NEAR(e.mass + e.removed_mass, e0.mass, 1e-12 * e0.mass);
  EXPECT_NEAR(e.kinetic + e.removed_energy, e0.kinetic, 1e-10 * e0.kinetic);
  for (const auto& [name, value] : s->result_values())
    if (name.rfind("momentum_change", 0) == 0) EXPECT_NEAR(value, 0.0, 1e-10 * norm(e0.momentum)) << name;
}

TEST(OtmActivation, ALaterBodyCannotJoinASharedNodeSet) {
  const std::string yaml = deck("plane_strain", "[0, 0, 0]",
                                "  - {name: late, material: rubber, shape: {type: box, lower: [0.065, 0.03], upper: "
                                "[0.08, 0.045]}, activation_time: 2.0e-5}\notm: {nodes: shared}\n");
  EXPECT_THROW(make(yaml), DeckError);
}

// Nodes at the vertices of the cells that hold points: a 6 x 4 cell box (h = 5 mm) has 7 x 5 nodes.
TEST(OtmNodes, VerticesOfTheOccupiedCells) {
  auto s = make(deck("plane_strain", "[0, 0, 0]"));
  EXPECT_EQ(s->nodes().size(), 7 * 5);
  for (const Vec3& x : s->nodes().x) {
    const double i = x[0] / 0.005, j = x[1] / 0.005;
    EXPECT_NEAR(i, std::round(i), 1e-9);
    EXPECT_NEAR(j, std::round(j), 1e-9);
    EXPECT_GE(x[0], 0.03 - 1e-12);
    EXPECT_LE(x[0], 0.06 + 1e-12);
  }
}

// Under gravity a free block accelerates uniformly: the central difference with the initial half
// step gives v_n+1/2 = v_0 + (n + 1/2) g dt for a constant dt, x_n = x_0 + v_0 t + g t^2 / 2 exactly.
TEST(OtmFreeBlockGravity, FollowsTheDiscreteTrajectory) {
  auto s = make(deck("plane_strain", "[1.0, 0, 0]", "loads:\n  - {type: body_force, acceleration: [0, -9.81, 0]}\n"));
  const double dt = 0.5 * s->stable_dt();
  const int steps = 20;
  for (int k = 0; k < steps; ++k) s->step(dt);
  const double t = steps * dt;
  const FieldStore& pts = s->points();
  const auto* x = pts.view<Vec3>("x");
  const auto* x0 = pts.view<Vec3>("x0");
  for (Index p = 0; p < pts.size(); ++p) {
    EXPECT_NEAR(x[p][0], x0[p][0] + 1.0 * t, 1e-13);
    EXPECT_NEAR(x[p][1], x0[p][1] - 0.5 * 9.81 * t * t, 1e-13);
  }
}

// One and two threads give bitwise identical states (node-wise gathers, fixed-chunk reductions).
TEST(OtmDeterminism, ThreadCountIndependent) {
  auto run = [](int threads) {
    set_threads(threads);
    auto s = make(deck("3d", "[30.0, -20.0, 10.0]", "loads:\n  - {type: body_force, acceleration: [0, -9.81e5, 0]}\n"));
    for (int k = 0; k < 20; ++k) s->step(s->stable_dt());
    const FieldStore& pts = s->points();
    return std::vector<Vec3>(pts.view<Vec3>("x"), pts.view<Vec3>("x") + pts.size());
  };
  const auto a = run(1), b = run(2);
  set_threads(max_threads());
  ASSERT_EQ(a.size(), b.size());
  for (size_t p = 0; p < a.size(); ++p)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(a[p][k], b[p][k]) << "point " << p;
}

}  // namespace
}  // namespace ballista::test_otm_solver
