// Decks that would run with wrong physics or fail with a misleading message are refused up front
// with the cause: overlapping bodies (every solver), face conditions and materials peridynamics
// cannot honour, a horizon the size of the body, a memory estimate from the actual family, the
// detonation's edge cases, a body thinner than its lattice, OTM support parameters that cannot
// work on the undeformed lattice. Each case is the reproduction of a defect that ran before.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_hardening_decks {

namespace fs = std::filesystem;
using namespace ballista;

namespace {

/// The message of what building the run's solver throws ("" if nothing).
std::string refusal(const std::string& deck, const std::vector<std::string>& overrides = {}) {
  try {
    make_solver(parse_deck(deck, "deck.yaml", overrides));
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A TNT slab driving a steel plate (plane strain, 0.5 mm lattice), as the explosive sandwich.
std::string sandwich(const std::string& solver) {
  return "simulation: {solver: " + solver +
         ", dimension: plane_strain, end_time: 1.0e-6}\n"
         "materials:\n"
         "  tnt: {preset: tnt}\n"
         "  steel: {model: linear_elastic, density: 7850, bulk_modulus: 160.0e9, shear_modulus: 79.0e9}\n"
         "grid: {lower: [-0.01, -0.01], upper: [0.01, 0.01], cell_size: 0.5e-3}\n"
         "bodies:\n"
         "  - {name: charge, material: tnt, shape: {type: box, lower: [-4.0e-3, -4.0e-3], upper: [2.0e-3, 4.0e-3]}}\n"
         "  - {name: plate, material: steel, shape: {type: box, lower: [2.0e-3, -4.0e-3], upper: [4.0e-3, 4.0e-3]}}\n"
         "detonation: {points: [{position: [-4.0e-3, 0], time: 0}]}\n";
}

// A 3D steel tube filled with a steel rod (a case and its fill, as the exploding cylinder).
const std::string kTubeAndFill =
    "simulation: {solver: mpm, dimension: 3d, end_time: 1.0e-6}\n"
    "materials:\n"
    "  steel: {model: linear_elastic, density: 7850, youngs_modulus: 2.0e11, poisson_ratio: 0.29}\n"
    "grid: {lower: [-0.02, -0.02, 0], upper: [0.02, 0.02, 0.02], cell_size: 1.0e-3}\n"
    "bodies:\n"
    "  - {name: case, material: steel, shape: {type: tube, center: [0, 0, 0], axis: z, radius: 0.016, "
    "inner_radius: 0.0127, length: 0.01}}\n"
    "  - {name: fill, material: steel, shape: {type: cylinder, center: [0, 0, 0], axis: z, radius: 0.0127, "
    "length: 0.01}}\n";

// The Kalthoff-Winkler plate of examples/pd_kalthoff_winkler.yaml, coarse.
const std::string kPlatePd =
    "simulation: {solver: peridynamics, dimension: plane_stress, end_time: 1.0e-6}\n"
    "peridynamics: {m: 3, fracture_energy: 22170, thickness: 0.009}\n"
    "materials:\n"
    "  steel: {model: linear_elastic, density: 8000, youngs_modulus: 190e9, poisson_ratio: 0.3333333333333333}\n"
    "grid: {lower: [-0.054, -0.104], upper: [0.124, 0.104], cell_size: 0.002}\n"
    "bodies:\n"
    "  - {name: plate, material: steel, shape: {type: box, lower: [0, -0.1], upper: [0.1, 0.1]}}\n";

}  // namespace

TEST(HardeningDecks, OverlappingBodiesAreRefusedInEverySolverNamingBothAndTheVolume) {
  // The plate moved 3 mm into the charge: 2 mm x 8 mm of it shared (the sandwich reproduction ran
  // with the plate at 249 m/s instead of 1324 in MPM).
  for (const char* solver : {"mpm", "peridynamics"}) {
    const std::string err = refusal(sandwich(solver), {"bodies.1.shape.lower=[0.0, -4.0e-3]"});
    EXPECT_TRUE(has(err, "bodies 'charge'") && has(err, "and 'plate'") && has(err, "overlap")) << solver << ": " << err;
    // The shared region is 2 mm x 8 mm = 1.6e-5 m^2 per metre of thickness, seen from either body's
    // points (both on 0.5 mm lattices): counted from the cells' volumes, within round-off.
    EXPECT_TRUE(has(err, "about 1.6e-05 m^3 per metre of thickness")) << solver << ": " << err;
    EXPECT_TRUE(has(err, "deck.yaml")) << err;
  }
  // The fill grown into its case (the exploding cylinder's reproduction collapsed its step).
  const std::string fill = refusal(kTubeAndFill, {"bodies.1.shape.radius=0.015"});
  EXPECT_TRUE(has(fill, "bodies 'case'") && has(fill, "'fill'")) << fill;
}

TEST(HardeningDecks, BodiesThatTouchOrFillACutoutAreAccepted) {
  EXPECT_EQ(refusal(sandwich("mpm")), "");           // the plate's face is the charge's face
  EXPECT_EQ(refusal(sandwich("peridynamics")), "");
  EXPECT_EQ(refusal(kTubeAndFill), "");              // the fill's radius is the bore
  // A body inside another's cutout: the hole is not the other body's space.
  const std::string deck =
      "simulation: {dimension: plane_strain, end_time: 1.0e-6}\n"
      "materials:\n  al: {model: linear_elastic, density: 2700, youngs_modulus: 7.0e10, poisson_ratio: 0.3}\n"
      "grid: {lower: [0, 0], upper: [0.01, 0.01], cell_size: 1.0e-3}\n"
      "bodies:\n"
      "  - {name: plate, material: al, shape: {type: box, lower: [0.001, 0.001], upper: [0.009, 0.009]}, "
      "cutouts: [{type: box, lower: [0.004, 0.004], upper: [0.006, 0.006]}]}\n"
      "  - {name: plug, material: al, shape: {type: box, lower: [0.004, 0.004], upper: [0.006, 0.006]}}\n";
  EXPECT_EQ(refusal(deck), "");
  EXPECT_TRUE(has(refusal(deck, {"bodies.1.shape.upper=[0.007, 0.006]"}), "overlap"));
}

TEST(HardeningDecks, PeridynamicsRefusesFaceConditionsItCannotImpose) {
  // A half plate with a "symmetry" face ran with points crossing the plane (no boundary code in
  // the bond solver): refused at the face's key instead.
  for (const char* bc : {"symmetry", "fixed", "wall"}) {
    const std::string err = refusal(kPlatePd, {std::string("grid.boundary={y_min: ") + bc + "}"});
    EXPECT_TRUE(has(err, "grid.boundary.y_min") && has(err, "imposes no " + std::string(bc))) << err;
  }
  EXPECT_EQ(refusal(kPlatePd, {"grid.boundary={y_min: free}"}), "");
}

TEST(HardeningDecks, PeridynamicsRefusesMaterialsWhoseModelItWouldReduce) {
  // Bonds take K and G only: a J2 or Johnson-Cook material ran as an elastic one.
  const std::string j2 = refusal(kPlatePd, {"materials.steel={model: j2_plasticity, density: 8000, youngs_modulus: "
                                            "190e9, poisson_ratio: 0.3, yield_stress: 1e9, hardening_modulus: 1e9}"});
  EXPECT_TRUE(has(j2, "materials.steel.model") && has(j2, "'j2_plasticity' is not elastic") &&
              has(j2, "peridynamics.yield_stress"))
      << j2;
  const std::string crit = refusal(kPlatePd, {"materials.steel.failure.criterion=max_stress",
                                              "materials.steel.failure.max_stress=1e9"});
  EXPECT_TRUE(has(crit, "failure.criterion")) << crit;
}

TEST(HardeningDecks, AHorizonAsLargeAsTheBodyIsRefused) {
  const std::string err = refusal(kPlatePd, {"peridynamics.m=", "peridynamics.horizon=1.0"});
  EXPECT_TRUE(has(err, "peridynamics.horizon") && has(err, "more than twice the largest extent of body 'plate' (0.2 m)")) << err;
  EXPECT_EQ(refusal(kPlatePd, {"peridynamics.m=", "peridynamics.horizon=0.01"}), "");
}

TEST(HardeningDecks, ThePeridynamicMemoryEstimateCountsTheActualFamily) {
  // m = 20 in 2D is ~1,250 bonds per point (the old estimate took the 3D family of m = 20, 27x
  // more, and refused this small run as needing 88 GB); m = 20 in 3D on a large body is refused
  // before any bond is built, naming the family.
  EXPECT_EQ(refusal(kPlatePd, {"peridynamics.m=20", "grid.cell_size=0.004"}), "");
  const std::string deck3 =
      "simulation: {solver: peridynamics, dimension: 3d, end_time: 1.0e-6}\n"
      "peridynamics: {m: 20}\n"
      "materials:\n  steel: {model: linear_elastic, density: 7850, youngs_modulus: 2.0e11, poisson_ratio: 0.25}\n"
      "grid: {lower: [0, 0, 0], upper: [0.2, 0.2, 0.2], cell_size: 0.002}\n"
      "bodies:\n  - {name: cube, material: steel, shape: {type: box, lower: [0, 0, 0], upper: [0.2, 0.2, 0.2]}}\n";
  const std::string err = refusal(deck3);
  EXPECT_TRUE(has(err, "families of 33400 bond ends per point")) << err;
}

TEST(HardeningDecks, DetonationEdgeCasesSayWhatIsWrong) {
  // A detonator at 1e308 s said "points are cut off from every detonator by inert material".
  EXPECT_TRUE(has(refusal(sandwich("mpm"), {"detonation.points.0.time=1e308"}), "at most 1 s"));
  // An explosive material no body uses said "spacing (0 m) must be positive".
  const std::string unused = refusal(sandwich("mpm"), {"bodies.0.material=steel"});
  EXPECT_TRUE(has(unused, "no body is made of an explosive material (material 'tnt'")) << unused;
  std::string unlit = sandwich("mpm");
  unlit.erase(unlit.find("detonation:"));
  EXPECT_EQ(refusal(unlit, {"bodies.0.material=steel"}), "");  // unused and unlit: an inert entry
}

TEST(HardeningDecks, AChargeOnAGradedGridIsLitOnTheLatticeOfItsCells) {
  // The program burn took its lattice from grid.cell_size: a charge inside a finer band of a graded
  // grid (points twice as close) was refused as "points closer than the lattice spacing".
  const std::string band = "grid.refine=[{axis: x, from: -0.005, to: 0.005, cell_size: 0.25e-3}, "
                           "{axis: y, from: -0.005, to: 0.005, cell_size: 0.25e-3}]";
  const Scenario sc = parse_deck(sandwich("mpm"), "deck.yaml", {band});
  auto solver = make_solver(sc);
  const FieldStore& pts = solver->points();
  const auto* x0 = pts.view<Vec3>("x0");
  const auto* lit = pts.real("lighting_time");
  const auto* bid = pts.ints("body");
  double D = 0.0;
  for (const auto& m : sc.materials)
    if (m.name == "tnt") D = m.params.at("detonation_speed");
  ASSERT_GT(D, 0.0);
  // Every point of the convex slab sees the detonator: its time is the straight distance over D
  // (the search's paths are exact along a line of sight; round-off only).
  int checked = 0;
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != 0) continue;
    const double d = std::hypot(x0[p][0] + 4.0e-3, x0[p][1]);
    EXPECT_NEAR(lit[p], d / D, 1e-9 * (d / D) + 1e-15) << p;
    ++checked;
  }
  EXPECT_EQ(checked, 48 * 64);  // 6 mm x 8 mm at 0.125 mm (two points per 0.25 mm cell and axis)
  // The burn takes burn_cells (2) lattice spacings of the points' own lattice at D.
  const auto* burn = pts.real("burn_time");
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == 0) EXPECT_NEAR(burn[p], 2.0 * 0.125e-3 / D, 1e-12 * (0.25e-3 / D)) << p;
  // A charge across cells of two sizes is not one lattice: refused, saying what to do.
  const std::string across = refusal(sandwich("mpm"), {"grid.refine=[{axis: x, from: -0.002, to: 0.005, cell_size: "
                                                       "0.25e-3}, {axis: y, from: -0.005, to: 0.005, cell_size: 0.25e-3}]"});
  EXPECT_TRUE(has(across, "cells of different sizes")) << across;
  EXPECT_TRUE(has(across, "one band of grid.refine")) << across;
}

TEST(HardeningDecks, ABodyThinnerThanItsLatticeSaysSo) {
  // 0.1 mm between the lattice columns at 1.875 and 2.125 mm: it said "no particles inside the grid".
  const std::string err = refusal(sandwich("mpm"), {"bodies.1.shape.upper=[2.1e-3, 4.0e-3]"});
  EXPECT_TRUE(has(err, "0.0001 m thick along x, less than its lattice spacing 0.00025 m")) << err;
}

TEST(HardeningDecks, OtmSupportParametersThatCannotWorkAreADeckError) {
  const std::string deck =
      "simulation: {solver: otm, dimension: plane_strain, end_time: 1.0e-6}\n"
      "otm: {gamma: 50}\n"
      "materials:\n  al: {model: linear_elastic, density: 2700, youngs_modulus: 7.0e10, poisson_ratio: 0.3}\n"
      "grid: {lower: [0, 0], upper: [0.01, 0.01], cell_size: 1.0e-3}\n"
      "bodies:\n  - {name: block, material: al, shape: {type: box, lower: [0.002, 0.002], upper: [0.008, 0.008]}}\n";
  const std::string err = refusal(deck);
  EXPECT_TRUE(has(err, "'otm.gamma'") && has(err, "on the undeformed lattice")) << err;
  EXPECT_EQ(refusal(deck, {"otm.gamma=1.8"}), "");
}

TEST(HardeningDecks, AnUnboundedOutputCountIsStatedWithoutInfinity) {
  const std::string err = refusal(sandwich("mpm"), {"simulation.end_time=1e308", "output.interval=1e-6"});
  EXPECT_TRUE(has(err, "more than 1e308 particle files")) << err;
  EXPECT_FALSE(has(err, "inf")) << err;
}

TEST(HardeningDecks, ASpeedBeyondLightIsADeckError) {
  const std::string err = refusal(sandwich("mpm"), {"bodies.1.velocity=[1e308, 0]"});
  EXPECT_TRUE(has(err, "below the speed of light")) << err;
}

TEST(HardeningDecks, PeridynamicSolidsWriteNoPlaceholderKinematics) {
  // Bonds leave F = I and zero stress on solid points: not written as if measured. The gas of an
  // explosive is fed F and has a pressure, so a run with one keeps them.
  const std::unique_ptr<Solver> solid = make_solver(parse_deck(kPlatePd, "plate.yaml"));
  for (const char* f : {"F", "stress", "R", "L", "half_size"}) EXPECT_FALSE(solid->points().info(f).output) << f;
  EXPECT_TRUE(solid->points().info("v").output);
  const std::unique_ptr<Solver> gas = make_solver(parse_deck(sandwich("peridynamics"), "sandwich.yaml"));
  for (const char* f : {"F", "stress"}) EXPECT_TRUE(gas->points().info(f).output) << f;
  EXPECT_FALSE(gas->points().info("R").output);
  EXPECT_TRUE(has(refusal(kPlatePd, {"output.domains=true"}), "no deforming domain"));
}

}  // namespace test_hardening_decks
