// OTM adaptivity (src/otm/otm_adaptivity.hpp, OtmSolver::regenerate_nodes) against exact
// statements:
//  - the split direction is the principal direction of the extent tensor (A u = lambda_max u);
//  - a split conserves every extensive quantity exactly (mass, volume, energies), copies the
//    state, places the children at the centres of the two halves of the parent's cell and halves
//    the cell along the split; children never cross a box face;
//  - a node re-generation conserves the linear momentum of every body to round-off and books its
//    kinetic-energy change, so the energy balance is unchanged; a uniform motion survives it
//    exactly (the interpolant of a constant field is the constant: partition of unity).
// Round-off: sums of a few hundred terms of size ~1 (1e-16 each); bounds 1e-12 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "deck/deck_reader.hpp"
#include "otm/lme_shape.hpp"
#include "otm/otm_adaptivity.hpp"
#include "otm/otm_solver.hpp"
#include "run/simulation.hpp"

namespace ballista::test_otm_adaptivity {
namespace {

// These tests are of the split's geometry and bookkeeping: the children copy the state
// (test_split_state.cpp interpolates it).
const otm::SplitStateSpec kCopy{false, {}};

TEST(OtmAdaptivity, LargestEigenvectorIsPrincipal) {
  // A = Q diag(5, 2, 0.5) Q^T with Q a rotation about (1, 2, 3); 2D: the upper 2x2 block.
  const Vec3 axis = (1.0 / std::sqrt(14.0)) * Vec3{{1.0, 2.0, 3.0}};
  const double c = std::cos(0.7), s = std::sin(0.7);
  Mat3 Q;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Q(i, j) = (i == j ? c : 0.0) + (1.0 - c) * axis[i] * axis[j];
  Q(0, 1) -= s * axis[2];
  Q(1, 0) += s * axis[2];
  Q(0, 2) += s * axis[1];
  Q(2, 0) -= s * axis[1];
  Q(1, 2) -= s * axis[0];
  Q(2, 1) += s * axis[0];
  const Mat3 A = Q * Mat3::diag(5.0, 2.0, 0.5) * transpose(Q);
  for (const int dim : {2, 3}) {
    double lo, hi;
    otm::symmetric_extremes(A, dim, lo, hi);
    const Vec3 u = otm::largest_eigenvector(A, dim, hi);
    EXPECT_NEAR(norm(u), 1.0, 1e-12);
    Vec3 Au;
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) Au[i] += A(i, j) * u[j];
    for (int i = 0; i < dim; ++i) EXPECT_NEAR(Au[i], hi * u[i], 1e-12 * hi) << "dim " << dim;
  }
  // Isotropic: any direction is principal; a unit vector comes back.
  EXPECT_NEAR(norm(otm::largest_eigenvector(Mat3::diag(2.0, 2.0, 2.0), 3, 2.0)), 1.0, 1e-15);
}

FieldStore two_points(double s0) {
  FieldStore f;
  f.add_real("x", 3, "m");
  f.add_real("x0", 3, "m");
  f.add_real("F", 9, "1");
  f.add_real(otm::kExtentField, 9, "m");
  f.add_real("half_size", 3, "m");
  f.add_real("mass", 1, "kg");
  f.add_real("volume", 1, "m^3");
  f.add_real("volume0", 1, "m^3");
  f.add_real("internal_energy", 1, "J");
  f.add_real("plastic_work", 1, "J");
  f.add_real("eqps", 1, "1");
  f.add_int("id", 1, "1");
  f.add_int("body", 1, "1");
  f.resize(2);
  auto* x = f.view<Vec3>("x");
  auto* x0 = f.view<Vec3>("x0");
  auto* F = f.view<Mat3>("F");
  auto* S = f.view<Mat3>(otm::kExtentField);
  auto* hs = f.view<Vec3>("half_size");
  for (Index p = 0; p < 2; ++p) {
    x0[p] = Vec3{{0.01 + 0.01 * static_cast<double>(p), 0.01, 0.01}};
    hs[p] = Vec3{{0.5 * s0, 0.5 * s0, 0.5 * s0}};
    f.real("mass")[p] = 2.0 + static_cast<double>(p);
    f.real("volume0")[p] = s0 * s0 * s0;
    f.real("internal_energy")[p] = 7.0;
    f.real("plastic_work")[p] = 3.0;
    f.real("eqps")[p] = 0.4;
    f.ints("id")[p] = p;
  }
  // Point 0 stretched 3x along x (split); point 1 by 1.5 (kept).
  F[0] = Mat3::diag(3.0, 1.0 / 3.0, 1.0);
  F[1] = Mat3::diag(1.5, 1.0, 1.0 / 1.5);
  for (Index p = 0; p < 2; ++p) {
    S[p] = s0 * F[p];
    x[p] = x0[p];
    f.real("volume")[p] = det(F[p]) * f.real("volume0")[p];
  }
  return f;
}

TEST(OtmAdaptivity, SplitConservesExtensiveQuantitiesAndCopiesState) {
  const double s0 = 1e-3;
  FieldStore f = two_points(s0);
  const std::vector<std::string> ext = {"mass", "volume0", "internal_energy", "plastic_work"};
  auto sum = [&](const std::string& name) {
    double t = 0.0;
    for (Index p = 0; p < f.size(); ++p) t += f.real(name)[p];
    return t;
  };
  const std::vector<std::string> conserved = {"mass", "volume", "volume0", "internal_energy", "plastic_work"};
  std::vector<double> before;
  for (const auto& name : conserved) before.push_back(sum(name));
  otm::AdaptivityOptions opt;
  opt.split_stretch = 2.0;
  std::int64_t next_id = 2;
  const Vec3 lower{{0.0, 0.0, 0.0}}, upper{{1.0, 1.0, 1.0}};
  const std::vector<Index> parents = otm::split_points(f, ext, {s0}, 3, false, lower, upper, opt, kCopy, "", next_id);
  ASSERT_EQ(parents.size(), 1u);
  EXPECT_EQ(parents[0], 0);
  ASSERT_EQ(f.size(), 3);
  EXPECT_EQ(next_id, 3);
  EXPECT_EQ(f.ints("id")[2], 2);
  for (size_t k = 0; k < conserved.size(); ++k)
    EXPECT_NEAR(sum(conserved[k]), before[k], 1e-15 * before[k]) << conserved[k];
  EXPECT_DOUBLE_EQ(f.real("mass")[0], 1.0);
  EXPECT_DOUBLE_EQ(f.real("mass")[2], 1.0);
  EXPECT_DOUBLE_EQ(f.real("eqps")[2], 0.4);
  const auto* x = f.view<Vec3>("x");
  const auto* x0 = f.view<Vec3>("x0");
  const auto* S = f.view<Mat3>(otm::kExtentField);
  const auto* hs = f.view<Vec3>("half_size");
  // Cell 3 s0 long along x: children at the centres of its halves, +-0.75 s0; reference offsets
  // +-0.25 s0; each child's cell 1.5 s0 long and its reference box half as long along x.
  EXPECT_NEAR(std::abs(x[0][0] - x[2][0]), 1.5 * s0, 1e-15);
  EXPECT_NEAR(x[0][0] + x[2][0], 2.0 * 0.01, 1e-15);
  EXPECT_NEAR(std::abs(x0[0][0] - x0[2][0]), 0.5 * s0, 1e-15);
  EXPECT_NEAR(std::abs(S[0](0, 0)), 1.5 * s0, 1e-15);
  EXPECT_NEAR(S[0](1, 1), s0 / 3.0, 1e-18);
  EXPECT_NEAR(hs[0][0], 0.25 * s0, 1e-18);
  EXPECT_NEAR(hs[2][1], 0.5 * s0, 1e-18);
  // A second pass splits nothing (1.5 s0 < 2 s0).
  EXPECT_TRUE(otm::split_points(f, ext, {s0}, 3, false, lower, upper, opt, kCopy, "", next_id).empty());
}

TEST(OtmAdaptivity, PointsNearAFaceAreNotSplit) {
  const double s0 = 1e-3;
  // Point 0 (cell 3 s0 long along x, children 0.75 s0 away along x) sits 1.4 s0 from the face
  // x = lower: a child would come closer than half that, and the offset has no component along
  // the face, so it stays whole; 1.6 s0 away it splits.
  const std::vector<std::string> ext = {"mass"};
  otm::AdaptivityOptions opt;
  std::int64_t next_id = 2;
  const Vec3 upper{{1.0, 1.0, 1.0}};
  FieldStore f = two_points(s0);
  EXPECT_TRUE(otm::split_points(f, ext, {s0}, 3, false, Vec3{{0.01 - 1.4 * s0, 0.0, 0.0}}, upper, opt, kCopy, "", next_id).empty());
  FieldStore g = two_points(s0);
  EXPECT_EQ(otm::split_points(g, ext, {s0}, 3, false, Vec3{{0.01 - 1.6 * s0, 0.0, 0.0}}, upper, opt, kCopy, "", next_id).size(), 1u);
}

TEST(OtmAdaptivity, FailedPointsAreNotSplit) {
  // Point 0 is stretched 3x (it splits when intact: SplitConservesExtensiveQuantitiesAndCopiesState);
  // failed, it carries no stress and stays whole.
  const double s0 = 1e-3;
  const std::vector<std::string> ext = {"mass"};
  otm::AdaptivityOptions opt;
  std::int64_t next_id = 2;
  FieldStore f = two_points(s0);
  f.add_real("failed", 1, "1");
  f.real("failed")[0] = 1.0;
  const Vec3 lower{{0.0, 0.0, 0.0}}, upper{{1.0, 1.0, 1.0}};
  EXPECT_TRUE(otm::split_points(f, ext, {s0}, 3, false, lower, upper, opt, kCopy, "failed", next_id).empty());
  f.real("failed")[0] = 0.0;
  EXPECT_EQ(otm::split_points(f, ext, {s0}, 3, false, lower, upper, opt, kCopy, "failed", next_id).size(), 1u);
}

TEST(OtmAdaptivity, AxisymmetricSplitSharesByTheHalfRings) {
  // A ring of reference radius r0 = 10 s0 stretched radially by 3 (F = diag(3, 1/3, 1)... with the
  // hoop stretch r / r0 of a ring now at 3 r0): children at r0 +- s0/4 in the reference carry
  // (r0 +- s0/4) / (2 r0) of the mass, their hoop stretch is their own r / r0 and V = J V0.
  const double s0 = 1e-3, r0 = 10.0 * s0;
  FieldStore f = two_points(s0);
  auto* x = f.view<Vec3>("x");
  auto* x0 = f.view<Vec3>("x0");
  auto* F = f.view<Mat3>("F");
  x0[0] = Vec3{{r0, 0.01, 0.0}};
  F[0] = Mat3::diag(3.0, 1.0 / 3.0, 3.0);
  x[0] = Vec3{{3.0 * r0, 0.01, 0.0}};
  f.real("volume")[0] = det(F[0]) * f.real("volume0")[0];
  const double m = f.real("mass")[0];
  const std::vector<std::string> ext = {"mass", "volume0", "internal_energy", "plastic_work"};
  otm::AdaptivityOptions opt;
  std::int64_t next_id = 2;
  ASSERT_EQ(otm::split_points(f, ext, {s0}, 2, true, Vec3{}, Vec3{{1.0, 1.0, 0.0}}, opt, kCopy, "", next_id).size(), 1u);
  x = f.view<Vec3>("x");
  x0 = f.view<Vec3>("x0");
  F = f.view<Mat3>("F");
  const Index a = x[0][0] > x[2][0] ? 0 : 2, b = 2 - a;  // outer, inner
  EXPECT_NEAR(x0[a][0], r0 + 0.25 * s0, 1e-15);
  EXPECT_NEAR(f.real("mass")[a], m * (r0 + 0.25 * s0) / (2.0 * r0), 1e-14 * m);
  EXPECT_NEAR(f.real("mass")[a] + f.real("mass")[b], m, 1e-15 * m);
  for (const Index p : {a, b}) {
    EXPECT_NEAR(F[p](2, 2), x[p][0] / x0[p][0], 1e-14);
    EXPECT_NEAR(f.real("volume")[p], det(F[p]) * f.real("volume0")[p], 1e-14 * f.real("volume")[p]);
  }
}

TEST(OtmAdaptivity, CrowdedNodesAreOnesOfOneBodyWithMass) {
  otm::NodeCloud c;
  c.x = {Vec3{{0.0, 0.0, 0.0}}, Vec3{{0.1e-3, 0.0, 0.0}}, Vec3{{5e-3, 0.0, 0.0}}};
  c.body = {0, 1, 0};
  c.mass = {1.0, 1.0, 1.0};
  c.v.resize(3);
  c.f.resize(3);
  EXPECT_FALSE(otm::nodes_crowded(c, 0.25e-3, 3));  // the close pair belongs to two bodies
  c.body = {0, 0, 0};
  EXPECT_TRUE(otm::nodes_crowded(c, 0.25e-3, 3));
  c.mass[1] = 0.0;
  EXPECT_FALSE(otm::nodes_crowded(c, 0.25e-3, 3));  // a node no point reaches does not count
}

// An elastic block (plane strain) hits a rigid wall; after 40 steps its velocity field is far
// from uniform. Re-generating the nodes then keeps the momentum along the free direction (the
// wall's normal y: no face holds it) and the energy balance.
TEST(OtmAdaptivity, RegenerationConservesMomentumAndBooksEnergy) {
  const std::string yaml = R"(
simulation: {solver: otm, dimension: plane_strain, end_time: 1.0e-4, cfl: 0.5}
materials:
  rubber: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
otm: {adaptivity: on}
grid: {lower: [0, 0], upper: [0.1, 0.1], cell_size: 0.005, boundary: {y_min: wall}}
bodies:
  - {name: block, material: rubber, shape: {type: box, lower: [0.03, 0.0], upper: [0.06, 0.03]},
     velocity: [4.0, -20.0, 0]}
)";
  const Scenario sc = parse_deck(yaml, "otm_regeneration.yaml");
  OtmSolver s(sc, make_materials(sc));
  for (int k = 0; k < 40; ++k) s.step(s.stable_dt());
  const EnergyTotals e0 = s.energies();
  s.regenerate_nodes();
  const EnergyTotals e1 = s.energies();
  EXPECT_GT(s.nodes().size(), 0);
  const double pscale = e0.mass * 20.0;
  EXPECT_NEAR(e1.momentum[0], e0.momentum[0], 1e-12 * pscale);
  EXPECT_NEAR(e1.momentum[1], e0.momentum[1], 1e-12 * pscale);
  // The kinetic energy changed (the field is not linear) and the change is booked.
  EXPECT_NE(e1.kinetic, e0.kinetic);
  EXPECT_NEAR(e1.transfer - e0.transfer, e1.kinetic - e0.kinetic, 1e-12 * e0.kinetic);
  EXPECT_NEAR(e1.total(), e0.total(), 1e-12 * e0.kinetic);
}

TEST(OtmAdaptivity, RegenerationKeepsAUniformMotion) {
  const std::string yaml = R"(
simulation: {solver: otm, dimension: 3d, end_time: 1.0e-4, cfl: 0.5}
materials:
  rubber: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
otm: {adaptivity: on}
grid: {lower: [0, 0, 0], upper: [0.1, 0.1, 0.1], cell_size: 0.005}
bodies:
  - {name: block, material: rubber, shape: {type: box, lower: [0.03, 0.03, 0.03], upper: [0.05, 0.06, 0.05]},
     velocity: [3.0, -2.0, 1.5]}
)";
  const Scenario sc = parse_deck(yaml, "otm_regeneration_uniform.yaml");
  OtmSolver s(sc, make_materials(sc));
  for (int k = 0; k < 10; ++k) s.step(s.stable_dt());  // translated by less than a cell
  const EnergyTotals e0 = s.energies();
  s.regenerate_nodes();
  const EnergyTotals e1 = s.energies();
  for (Index a = 0; a < s.nodes().size(); ++a) {
    if (!(s.nodes().mass[a] > 0.0)) continue;
    EXPECT_NEAR(s.nodes().v[a][0], 3.0, 1e-12);
    EXPECT_NEAR(s.nodes().v[a][1], -2.0, 1e-12);
    EXPECT_NEAR(s.nodes().v[a][2], 1.5, 1e-12);
  }
  EXPECT_NEAR(e1.kinetic, e0.kinetic, 1e-12 * e0.kinetic);
  EXPECT_NEAR(e1.transfer, 0.0, 1e-12 * e0.kinetic);
}

}  // namespace
}  // namespace ballista::test_otm_adaptivity
