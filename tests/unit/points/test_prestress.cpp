// A target that starts in its confinement's stress (`confinement` with `prestress: true`,
// points/prestress.hpp): the stress reached, the stretches that carry it against Hooke's law, the
// points moved with them, the geomodel's state, and the deck's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <yaml-cpp/yaml.h>

#include "core/point_fields.hpp"
#include "deck/deck_reader.hpp"
#include "points/point_set.hpp"
#include "points/prestress.hpp"
#include "run/simulation.hpp"
#include "support/deck_errors.hpp"
#include "support/test_files.hpp"

namespace ballista::test_prestress {
namespace {

// An elastic rock cylinder (E = 20 GPa, nu = 0.2), radial 20 MPa and axial 30 MPa, axisymmetric.
std::string deck(const std::string& rock, const std::string& load) {
  return R"(simulation: {dimension: axisymmetric, end_time: 1.0e-6}
grid: {lower: [0, -0.005], upper: [0.016, 0.03], cell_size: 1.0e-3}
materials:
  rock: )" + rock + R"(
bodies:
  - name: target
    material: rock
    shape: {type: cylinder, center: [0, 0.002], axis: y, radius: 0.01, length: 0.02}
loads:
  - )" + load + "\n";
}

const std::string kElastic = "{model: linear_elastic, density: 2300, youngs_modulus: 20e9, poisson_ratio: 0.2}";
const std::string kLoad = "{type: confinement, body: target, radial: 20e6, axial: 30e6, prestress: true}";
// kLoad's stress along the radius, the axis and the radius again (tension positive), and kElastic.
const double kSr = -20e6, kSz = -30e6, kE = 20e9, kNu = 0.2;
// The model is hypoelastic (linear_elastic.cpp): along a path of fixed principal axes its stress
// is Hooke's law of the logarithmic strain, so ln(lambda_i) = (s_i - nu (s_j + s_k)) / E.
const double kEr = (kSr - kNu * (kSz + kSr)) / kE, kEz = (kSz - 2.0 * kNu * kSr) / kE;

/// A point's stress reached to the drive's tolerance (1e-9 of the largest stress), and its radial
/// and axial stretches against Hooke's law. The adapter's strain increment is a midpoint rule,
/// exact to O(increment^3) per increment (20 increments of ~5e-5): 1e-9 of the strain is far above
/// that and far below a wrong law.
void expect_hooke(const Mat3& S, const Mat3& F) {
  EXPECT_NEAR(S(0, 0), kSr, 1e-8 * 30e6);
  EXPECT_NEAR(S(1, 1), kSz, 1e-8 * 30e6);
  EXPECT_NEAR(S(2, 2), kSr, 1e-8 * 30e6);
  EXPECT_NEAR(std::log(F(0, 0)), kEr, 1e-9 + 1e-6 * std::abs(kEr));
  EXPECT_NEAR(std::log(F(1, 1)), kEz, 1e-9 + 1e-6 * std::abs(kEz));
}

TEST(Prestress, ElasticCylinderCarriesTheLoadsStressWithHookesStretches) {
  const Scenario sc = parse_deck(deck(kElastic, kLoad), "prestress.yaml");
  PointSet pts(sc, make_materials(sc), SeedLattice{sc.grid, 0}, 0.0, "");
  FieldStore& s = pts.store();
  const Index n = s.size();
  ASSERT_GT(n, 100);
  const Mat3* F = s.view(kDeformationGradient);
  const Mat3* S = s.view(kStress);
  const Vec3* x = s.view(kPosition);
  const Vec3* x0 = s.view(kReferencePosition);
  const double* V = s.real(kVolume);
  const double* V0 = s.real(kReferenceVolume);
  for (Index p = 0; p < n; ++p) {
    expect_hooke(S[p], F[p]);
    EXPECT_NEAR(S[p](0, 1), 0.0, 1e-8 * 30e6);
    EXPECT_NEAR(std::log(F[p](2, 2)), kEr, 1e-9 + 1e-6 * std::abs(kEr));  // the hoop stretch is r / r0
    EXPECT_NEAR(V[p], F[p](0, 0) * F[p](1, 1) * F[p](2, 2) * V0[p], 1e-14 * V0[p]);
    // Moved with F about the axis and the cylinder's mid-height (y = 12 mm: it spans 2 to 22 mm; a symmetric lattice).
    EXPECT_NEAR(x[p][0], F[p](0, 0) * x0[p][0], 1e-15);
    EXPECT_NEAR(x[p][1] - 0.012, F[p](1, 1) * (x0[p][1] - 0.012), 1e-12);
  }
}

TEST(Prestress, ThreeDimensionalCylinderAlongYIsStretchedAboutItsCentre) {
  // The same rock and load in 3D: the axial stress along the cylinder's axis (y), the radial one
  // along x and z; points moved about the centre of mass, here the cylinder's centre (0, 12 mm, 0).
  const Scenario sc = parse_deck(R"(simulation: {dimension: 3d, end_time: 1.0e-6}
grid: {lower: [-0.012, -0.002, -0.012], upper: [0.012, 0.026, 0.012], cell_size: 2.0e-3}
materials:
  rock: )" + kElastic + R"(
bodies:
  - name: target
    material: rock
    shape: {type: cylinder, center: [0, 0.002, 0], axis: y, radius: 0.01, length: 0.02}
loads:
  - )" + kLoad + "\n",
                                 "prestress3d.yaml");
  PointSet pts(sc, make_materials(sc), SeedLattice{sc.grid, 0}, 0.0, "");
  FieldStore& s = pts.store();
  const Mat3* F = s.view(kDeformationGradient);
  const Mat3* S = s.view(kStress);
  const Vec3* x = s.view(kPosition);
  const Vec3* x0 = s.view(kReferencePosition);
  const Vec3 c{{0.0, 0.012, 0.0}};
  for (Index p = 0; p < s.size(); ++p) {
    expect_hooke(S[p], F[p]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(x[p][i] - c[i], F[p](i, i) * (x0[p][i] - c[i]), 1e-12);
  }
}

TEST(Prestress, GeomodelRockIsPrestressedElasticallyWithItsStateUntouched) {
  const Scenario sc = parse_deck(deck("{preset: sandstone_berea_drained}",
                                      "{type: confinement, body: target, pressure: 34.48e6, prestress: true}"),
                                 "prestress.yaml");
  PointSet pts(sc, make_materials(sc), SeedLattice{sc.grid, 0}, 0.0, "");
  FieldStore& s = pts.store();
  const Mat3* S = s.view(kStress);
  const Mat3* F = s.view(kDeformationGradient);
  const double* eqps = s.real("eqps");
  const double* evp = s.real("plastic_volumetric_strain");
  for (Index p = 0; p < s.size(); ++p) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(S[p](i, i), -34.48e6, 1e-8 * 34.48e6);
    // 34.5 MPa is inside Berea's elastic domain (the damped stage's end state has eqps = 0 too).
    EXPECT_EQ(eqps[p], 0.0);
    EXPECT_EQ(evp[p], 0.0);
    // Compressed by p / K with K between B0 and B0 + B1: J between 0.99 and 1.
    const double J = F[p](0, 0) * F[p](1, 1) * F[p](2, 2);
    EXPECT_LT(J, 1.0);
    EXPECT_GT(J, 0.99);
  }
}

/// Kinetic energy (J) at the end of 20 us of the deck with this load, no stage.
double kinetic_after_20us(const std::string& load) {
  test::TempDir dir;
  RunOptions o;
  o.out_dir = dir.path.string();
  o.progress = false;
  const RunResult r =
      run_simulation(parse_deck(deck(kElastic, load), "prestress.yaml", {"simulation.end_time=20e-6"}), o);
  EXPECT_TRUE(r.ok) << r.error;
  return YAML::LoadFile((dir.path / "summary.json").string())["energy"]["kinetic"].as<double>();
}

TEST(Prestress, StaysInEquilibriumWhenRunWithoutAStage) {
  // Prestressed and held by the full load from t = 0, the cylinder should not move: the uniform
  // stress is the exact equilibrium of these tractions, and the discrete one only differs where
  // the surface tractions meet the grid. The same load applied suddenly to the unstressed cylinder
  // rings with a kinetic energy of the order of its elastic energy (sigma^2 / 2K per volume); the
  // prestressed one must keep less than 1e-3 of that (what is left is the discrete mismatch at
  // the surface; a wrong stress, stretch or position would give order 1).
  const double sudden = kinetic_after_20us("{type: confinement, body: target, radial: 20e6, axial: 30e6}");
  const double prestressed = kinetic_after_20us(kLoad);
  EXPECT_GT(sudden, 0.0);
  EXPECT_LT(prestressed, 1e-4 * sudden) << "sudden " << sudden << " J, prestressed " << prestressed << " J";
}

TEST(Prestress, DeckRefusesARampAPlaneStrainTargetAndAnotherInitialState) {
  const DeckError ramp = test::parse_error(
      deck(kElastic, "{type: confinement, body: target, pressure: 1e6, prestress: true, curve: [[0, 0], [1e-5, 1]]}"));
  EXPECT_NE(ramp.key_path().find("curve"), std::string::npos) << ramp.what();
  EXPECT_NE(std::string(ramp.what()).find("full load from t = 0"), std::string::npos) << ramp.what();
  std::string plane = deck(kElastic, kLoad);
  plane.replace(plane.find("axisymmetric"), 12, "plane_strain");
  const DeckError ps = test::parse_error(plane);
  EXPECT_NE(ps.key_path().find("prestress"), std::string::npos) << ps.what();
  std::string mms = deck(kElastic, kLoad);
  mms.replace(mms.find("    material: rock"), 18, "    material: rock\n    initial_state: mms_axis_aligned");
  const DeckError other = test::parse_error(mms);
  EXPECT_NE(other.key_path().find("prestress"), std::string::npos) << other.what();
  EXPECT_NE(std::string(other.what()).find("mms_axis_aligned"), std::string::npos) << other.what();
}

TEST(Prestress, BeyondTheMaterialsStrengthIsADeckErrorNamingTheBody) {
  // J2 steel (yield 350 MPa) under 1 GPa radial and nothing axial: a deviatoric stress it cannot hold.
  const Scenario sc = parse_deck(
      deck("{model: j2_plasticity, density: 7850, youngs_modulus: 200e9, poisson_ratio: 0.3, yield_stress: 350e6}",
           "{type: confinement, body: target, radial: 1e9, axial: 0, prestress: true}"),
      "prestress.yaml");
  const DeckError e = test::deck_error([&] { PointSet pts(sc, make_materials(sc), SeedLattice{sc.grid, 0}, 0.0, ""); });
  EXPECT_NE(std::string(e.what()).find("cannot be prestressed"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("target"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace ballista::test_prestress
