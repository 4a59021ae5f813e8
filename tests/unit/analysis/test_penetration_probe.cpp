// Penetration probe on hand-placed particles: depth of the deepest penetrator particle, cavity
// tip, kinetic energy per segment, penetrator points beyond the tunnel's end, and the summary's
// hydrodynamic values (thesis eq. 3.1-3.2).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "analysis/penetration_probe.hpp"
#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_penetration_probe {

using namespace ballista;

namespace {

// Target top face at y = 0.02; a segmented rod (2 pieces of 2 mm, gap 2 mm) nose at y = 0.021.
const char* kDeck = R"(simulation: {dimension: axisymmetric, end_time: 1.0e-6}
grid: {lower: [0, 0], upper: [0.01, 0.04], cell_size: 1.0e-3}
materials:
  rock: {model: linear_elastic, density: 2300, youngs_modulus: 20e9, poisson_ratio: 0.2}
  w: {model: linear_elastic, density: 18400, youngs_modulus: 350e9, poisson_ratio: 0.3}
bodies:
  - {name: target, material: rock, shape: {type: cylinder, center: [0, 0], axis: y, radius: 0.008, length: 0.02}}
  - name: rod
    material: w
    rod: {nose: [0, 0.021], diameter: 2e-3, length: 4e-3, speed: 1000, segment_ld: 1.0}
penetration: {penetrator: rod, target: target}
)";

TEST(PenetrationProbe, DepthCavityAndSegmentEnergies) {
  const Scenario sc = parse_deck(kDeck, "probe.yaml");
  auto solver = make_solver(sc);
  FieldStore& pts = solver->points();
  PenetrationProbe probe(sc);
  auto* x = pts.view<Vec3>("x");
  auto* v = pts.view<Vec3>("v");
  const auto* bid = pts.ints("body");
  const auto* seg = pts.ints("segment");
  const auto* m = pts.real("mass");

  // Before anything moves: no penetrator below the face; the cavity tip is the face itself
  // (the top of the surface particles' domains, 0 within round-off).
  auto row = probe.sample(pts, true, 0.0, solver->reporting_scale());
  EXPECT_EQ(row[1], 0.0);
  EXPECT_NEAR(row[2], 0.0, 1e-15);
  // KE per segment = sum 1/2 m v^2 x 2 pi (axisymmetric per-radian masses).
  double e0 = 0, e1 = 0;
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == 1) (seg[p] == 0 ? e0 : e1) += 0.5 * m[p] * 1000.0 * 1000.0 * 2 * std::numbers::pi;
  EXPECT_GT(e0, 0.0);
  EXPECT_NEAR(row[4], e0, 1e-12 * e0);
  EXPECT_NEAR(row[5], e1, 1e-12 * e1);
  EXPECT_NEAR(row[3], e0 + e1, 1e-12 * (e0 + e1));

  // Push one rod particle 7 mm below the face and clear the target near the axis down to 5 mm
  // (move those particles sideways): depth 7 mm; cavity tip at the top of the first particle
  // left on the axis (centre 5.25 mm below, domain half-height 0.25 mm).
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] == 1 && seg[p] == 1) {
      x[p][1] = 0.02 - 0.007;
      v[p] = Vec3{};
      break;
    }
  }
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == 0 && x[p][0] < 1e-3 && x[p][1] > 0.02 - 0.005) x[p][0] += 0.004;
  row = probe.sample(pts, true, 1e-6, solver->reporting_scale());
  EXPECT_NEAR(row[1], 0.007, 1e-15);
  EXPECT_NEAR(row[2], 0.005, 1e-12);
  EXPECT_NEAR(probe.depth_of(Vec3{{0, 0.015, 0}}), 0.005, 1e-15);
  EXPECT_NEAR(probe.lateral_of(Vec3{{0.003, 0.015, 0}}), 0.003, 1e-15);

  test::TempDir dir;
  JsonValue out;
  probe.finish(pts, dir.path.string(), 1e-6, out);
  // Hydrodynamic theory, eq. 3.1-3.2: U_h = V / (1 + sqrt(rho_t/rho_p)), P = L sqrt(rho_p/rho_t).
  EXPECT_NEAR(out.at("hydrodynamic_rate").as_number(), 1000.0 / (1.0 + std::sqrt(2300.0 / 18400.0)), 1e-9);
  EXPECT_NEAR(out.at("hydrodynamic_depth").as_number(), 4e-3 * std::sqrt(8.0), 1e-15);
  EXPECT_EQ(out.at("segments").as_int(), 2);
  EXPECT_EQ(out.at("analytic").size(), 2u);  // Birkhoff and, segmented, the particulated bound
  EXPECT_NEAR(out.at("final_depth").as_number(), 0.007, 1e-15);
  EXPECT_TRUE(std::filesystem::exists(dir.path / "penetration.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir.path / "channel.csv"));
  // Channel: the cleared core (r < 1 mm, moved 4 mm out) leaves material from r = 1 mm (centre
  // 1.25 mm less the domain half-width) in the top 5 mm; below it the channel is closed.
  EXPECT_NEAR(out.at("max_channel_radius").as_number(), 1e-3, 1e-12);
}

TEST(PenetrationProbe, PenetratorPointsFarBeyondTheTunnelAreCounted) {
  const Scenario sc = parse_deck(kDeck, "probe.yaml");
  auto solver = make_solver(sc);
  FieldStore& pts = solver->points();
  auto* x = pts.view<Vec3>("x");
  const auto* bid = pts.ints("body");
  const auto* m = pts.real("mass");
  // The tunnel open to 5 mm below the face (the core r < 1 mm moved aside), the rod above the face
  // except one point.
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == 0 && x[p][0] < 1e-3 && x[p][1] > 0.02 - 0.005) x[p][0] += 0.004;
  Index stray = -1;
  double rod_mass = 0.0;
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == 1) {
      rod_mass += m[p];
      if (stray < 0) stray = p;
    }
  const auto beyond_with_stray_at = [&](double depth) {
    x[stray][1] = 0.02 - depth;
    PenetrationProbe probe(sc);
    probe.sample(pts, true, 0.0, solver->reporting_scale());
    test::TempDir dir;
    JsonValue out;
    probe.finish(pts, dir.path.string(), 1e-6, out);
    return out.at("beyond_tunnel");
  };
  // 12 mm deep, 7 mm (7 cells) beyond the tunnel's end: counted, with its share of the rod's mass.
  JsonValue b = beyond_with_stray_at(0.012);
  EXPECT_NEAR(b.at("tunnel_end").as_number(), 0.005, 1e-12);
  EXPECT_NEAR(b.at("margin").as_number(), 2e-3, 1e-15);  // kBeyondTunnelCells of 1 mm
  EXPECT_EQ(b.at("points").as_int(), 1);
  EXPECT_NEAR(b.at("deepest").as_number(), 0.012, 1e-15);
  EXPECT_NEAR(b.at("mass_share").as_number(), m[stray] / rod_mass, 1e-15);
  // 6.5 mm deep, 1.5 cells beyond: a point driving the floor, not counted.
  b = beyond_with_stray_at(0.0065);
  EXPECT_EQ(b.at("points").as_int(), 0);
  EXPECT_EQ(b.at("deepest").kind(), JsonValue::Kind::Null);
  // The whole core moved aside (perforated on the axis): no tunnel's end, nothing measured.
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == 0 && x[p][0] < 1e-3) x[p][0] += 0.004;
  EXPECT_EQ(beyond_with_stray_at(0.012).kind(), JsonValue::Kind::Null);
}

// A 2 mm steel plate above the rock (y 22-24 mm) and the segmented tungsten rod (2 x 2 mm, 2 mm
// in diameter) with its nose at 25 mm: the layer the jet-remainder record is taken behind.
const char* kLayeredDeck = R"(simulation: {dimension: axisymmetric, end_time: 1.0e-6}
grid: {lower: [0, 0], upper: [0.01, 0.04], cell_size: 1.0e-3}
materials:
  rock: {model: linear_elastic, density: 2300, youngs_modulus: 20e9, poisson_ratio: 0.2}
  steel: {model: linear_elastic, density: 7850, youngs_modulus: 200e9, poisson_ratio: 0.3}
  w: {model: linear_elastic, density: 18400, youngs_modulus: 350e9, poisson_ratio: 0.3}
bodies:
  - {name: target, material: rock, shape: {type: cylinder, center: [0, 0], axis: y, radius: 0.008, length: 0.02}}
  - {name: plate, material: steel, shape: {type: cylinder, center: [0, 0.022], axis: y, radius: 0.008, length: 0.002}}
  - name: rod
    material: w
    rod: {nose: [0, 0.025], diameter: 2e-3, length: 4e-3, speed: 1000, segment_ld: 1.0}
penetration: {penetrator: rod, target: target, layers: [plate]}
)";

/// The probe's summary after one sample of the solver's points as they are now (t = 0).
JsonValue summary_of_one_sample(const Scenario& sc, Solver& solver) {
  PenetrationProbe probe(sc);
  probe.sample(solver.points(), true, 0.0, solver.reporting_scale());
  test::TempDir dir;
  JsonValue out;
  probe.finish(solver.points(), dir.path.string(), 1e-6, out);
  return out;
}

TEST(PenetrationProbe, JetRemainderBehindALayer) {
  const Scenario sc = parse_deck(kLayeredDeck, "layers.yaml");
  auto solver = make_solver(sc);
  FieldStore& pts = solver->points();
  PenetrationProbe probe(sc);
  auto* x = pts.view<Vec3>("x");
  auto* v = pts.view<Vec3>("v");
  const auto* bid = pts.ints("body");
  const auto* seg = pts.ints("segment");
  const double scale = solver->reporting_scale();
  // Nose 1 mm above the plate: nothing is recorded.
  probe.sample(pts, true, 0.0, scale);
  // Erode the leading row of segment 0 (the lowest of its four 0.5 mm rows: stopped, as eroded
  // jet leaving the stagnation point) and put one intact point of it below the plate's back face.
  // On the axisymmetric lattice the row's mass x 2 pi is exactly rho pi r^2 x 0.5 mm (particle
  // radii 0.25 and 0.75 mm, sum r dr = R^2 / 2), so the consumed length is 0.5 mm exactly.
  double lowest = 1.0;
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == 2 && seg[p] == 0) lowest = std::min(lowest, x[p][1]);
  Index moved = -1;
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != 2 || seg[p] != 0) continue;
    if (x[p][1] < lowest + 1e-9) v[p] = Vec3{{0, 500.0, 0}};  // going back: eroded
    else if (moved < 0) moved = p;
  }
  ASSERT_GE(moved, 0);
  x[moved][1] = 0.0215;
  probe.sample(pts, true, 1e-6, scale);

  test::TempDir dir;
  JsonValue out;
  probe.finish(pts, dir.path.string(), 1e-6, out);
  const JsonValue& j = out.at("holes").at("plate").at("jet_behind");
  EXPECT_TRUE(j.at("reached").as_bool());
  EXPECT_EQ(j.at("time").as_number(), 1e-6);
  EXPECT_NEAR(j.at("consumed_length").as_number(), 0.5e-3, 1e-15);
  EXPECT_NEAR(j.at("remaining_length").as_number(), 3.5e-3, 1e-15);
  EXPECT_NEAR(j.at("tip_velocity").as_number(), 1000.0, 1e-9);  // the intact rows keep their speed
  EXPECT_EQ(j.at("tip_segment").as_number(), 0.0);
  // Thesis eq. 3.2 inverted: the plate consumes T sqrt(rho_plate / rho_rod) of the rod.
  EXPECT_NEAR(j.at("hydrodynamic_consumed_length").as_number(), 2e-3 * std::sqrt(7850.0 / 18400.0), 1e-15);

  // The record survives a checkpoint, and not in a state saved before it was taken.
  StateArchive all, before;
  probe.save_state(all);
  probe.save_state(before, 1);
  PenetrationProbe restored(sc), earlier(sc);
  restored.load_state(all);
  earlier.load_state(before);
  JsonValue out2, out3;
  restored.finish(pts, dir.path.string(), 1e-6, out2);
  earlier.finish(pts, dir.path.string(), 1e-6, out3);
  EXPECT_EQ(out2.at("holes").at("plate").at("jet_behind").at("consumed_length").as_number(), 0.5e-3);
  EXPECT_FALSE(out3.at("holes").at("plate").at("jet_behind").at("reached").as_bool());
}

// A shaped charge's liner as the penetrator: its jet forms in the run and flies along the liner's
// axis from the apex (y = 2 mm) towards the mouth (+y), through a plate into a target above it; the
// charge behind the apex is not a layer.
const char* kFormedJetDeck = R"(simulation: {dimension: axisymmetric, end_time: 1.0e-6}
grid: {lower: [0, 0], upper: [0.02, 0.06], cell_size: 1.0e-3}
materials:
  rock: {model: linear_elastic, density: 2300, youngs_modulus: 20e9, poisson_ratio: 0.2}
  steel: {model: linear_elastic, density: 7850, youngs_modulus: 200e9, poisson_ratio: 0.3}
  cu: {model: linear_elastic, density: 8930, youngs_modulus: 120e9, poisson_ratio: 0.34}
  tnt: {preset: tnt}
bodies:
  - {name: liner, material: cu, shape: {type: liner, center: [0, 0.002], axis: y, angle: 60, thickness: 1.5e-3, diameter: 0.016}}
  - {name: charge, material: tnt, shape: {type: cylinder, center: [0, 0], axis: y, radius: 0.009, length: 0.002}}
  - {name: plate, material: steel, shape: {type: cylinder, center: [0, 0.03], axis: y, radius: 0.009, length: 0.002}}
  - {name: target, material: rock, shape: {type: cylinder, center: [0, 0.034], axis: y, radius: 0.009, length: 0.02}}
detonation: {points: [{position: [0, 0.0005], time: 0}]}
penetration: {penetrator: liner, target: target, end_when_spent: 0.01}
)";

TEST(PenetrationProbe, AJetFormedInTheRunFliesAlongItsLinersAxisAndReportsNoTheory) {
  const Scenario sc = parse_deck(kFormedJetDeck, "formed.yaml");
  ASSERT_TRUE(sc.penetration.formed_jet);
  EXPECT_EQ(sc.penetration.flight.axis, 1);
  EXPECT_EQ(sc.penetration.flight.direction, 1.0);    // from the apex towards the mouth
  EXPECT_EQ(sc.penetration.surface, 0.034);           // the target's face towards the liner
  EXPECT_EQ(sc.penetration.layers, std::vector<std::string>{"plate"});  // not the charge
  auto solver = make_solver(sc);
  FieldStore& pts = solver->points();
  PenetrationProbe probe(sc);
  auto* x = pts.view<Vec3>("x");
  const auto* bid = pts.ints("body");
  // One liner point 5 mm into the target (its centre): the depth is +y below the face.
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == 0) {
      x[p] = Vec3{{0.0005, 0.039, 0}};
      break;
    }
  const auto row = probe.sample(pts, true, 1e-6, solver->reporting_scale());
  EXPECT_NEAR(row[1], 0.005, 1e-15);
  EXPECT_NEAR(probe.depth_of(Vec3{{0, 0.030, 0}}), -0.004, 1e-15);

  test::TempDir dir;
  JsonValue out;
  probe.finish(pts, dir.path.string(), 1e-6, out);
  EXPECT_TRUE(out.at("formed_jet").as_bool());
  EXPECT_NEAR(out.at("final_depth").as_number(), 0.005, 1e-15);
  // What only the deck of a rod or a jet table states is not known: null, not a number.
  for (const char* key : {"impact_velocity", "penetrator_length", "hydrodynamic_rate", "hydrodynamic_depth",
                          "cells_across_radius", "rate_over_hydrodynamic"})
    EXPECT_EQ(out.at(key).kind(), JsonValue::Kind::Null) << key;
  EXPECT_FALSE(out.at("resolved").as_bool());
  EXPECT_EQ(out.at("analytic").size(), 0u);
  EXPECT_EQ(out.at("holes").at("plate").at("jet_behind").kind(), JsonValue::Kind::Null);

  // end_when_spent: the liner is all in and at rest at t = 0, so its energy must fall from its peak
  // (not from its energy when it came in, which is 0) to the share of it.
  PenetrationProbe spent(sc);
  auto* v = pts.view<Vec3>("v");
  const auto set_speed = [&](double s) {
    for (Index p = 0; p < pts.size(); ++p)
      if (bid[p] == 0) v[p] = Vec3{{0, s, 0}};
  };
  set_speed(0.0);
  spent.sample(pts, true, 0.0, solver->reporting_scale());
  set_speed(1000.0);
  spent.sample(pts, true, 1e-6, solver->reporting_scale());
  EXPECT_FALSE(spent.spent());
  set_speed(150.0);  // 2.25 % of the peak energy: above the 1 % share
  spent.sample(pts, true, 2e-6, solver->reporting_scale());
  EXPECT_FALSE(spent.spent());
  set_speed(90.0);  // 0.81 %
  spent.sample(pts, true, 3e-6, solver->reporting_scale());
  EXPECT_TRUE(spent.spent());
  // A rod's summary has no formed_jet key (its summary is what it was).
  const Scenario rod = parse_deck(kLayeredDeck, "layers.yaml");
  EXPECT_FALSE(rod.penetration.formed_jet);
  auto rod_solver = make_solver(rod);
  EXPECT_FALSE(summary_of_one_sample(rod, *rod_solver).contains("formed_jet"));
}

TEST(PenetrationProbe, HoleOfADisplacedPlateIsMeasuredInThePlate) {
  // A 2 mm hole (radius) through the plate, and the whole plate then pushed 1.5 mm down the line
  // of flight, as the jet's blast dishes a casing. The entrance hole is read in the plate's own
  // seeded slices: 4 mm across (fixed bins would find no plate at the struck face's slice).
  const Scenario sc = parse_deck(kLayeredDeck, "layers.yaml");
  auto solver = make_solver(sc);
  FieldStore& pts = solver->points();
  auto* x = pts.view<Vec3>("x");
  const auto* bid = pts.ints("body");
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != 1) continue;
    if (x[p][0] < 2e-3) x[p][0] += 0.02;  // the hole's material thrown far out, beyond the plate
    x[p][1] -= 1.5e-3;
  }
  const JsonValue out = summary_of_one_sample(sc, *solver);
  const JsonValue& h = out.at("holes").at("plate");
  // Annuli of the 1 mm lateral cell; the hole's edge lies on one of their edges.
  EXPECT_NEAR(h.at("entrance_diameter").as_number(), 4e-3, 1e-12);
  EXPECT_NEAR(h.at("min_diameter").as_number(), 4e-3, 1e-12);
  EXPECT_NEAR(h.at("mean_diameter").as_number(), 4e-3, 1e-12);
  // One slice per 1 mm cell of the 2 mm plate, each through the straight hole.
  ASSERT_EQ(h.at("diameters").size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_NEAR(h.at("diameters").at(k).as_number(), 4e-3, 1e-12);
  EXPECT_TRUE(h.at("perforated").as_bool());
}

TEST(PenetrationProbe, FailedPointsAreDebrisOnlyWhereTheirFailureErodesThem) {
  // A 2 mm hole (radius) through the plate and a ring of failed points from 2 to 3 mm around it.
  // Whether the ring is wall follows the plate's failure.erosion: with `none` a failed point keeps
  // its model's stress and is solid (hole 4 mm across); with `zero_stress` it carries nothing and
  // is debris (hole 6 mm across). Annuli of the 1 mm lateral cell: both edges lie on their edges.
  for (const auto& [erosion, diameter] : {std::pair{"none", 4e-3}, std::pair{"zero_stress", 6e-3}}) {
    std::string deck = kLayeredDeck;
    const std::string steel = "poisson_ratio: 0.3}\n  w:";
    deck.replace(deck.find(steel), steel.size(),
                 std::string("poisson_ratio: 0.3, failure: {criterion: max_stress, max_stress: 1.0e9, erosion: ") +
                     erosion + "}}\n  w:");
    const Scenario sc = parse_deck(deck, "layers.yaml");
    auto solver = make_solver(sc);
    FieldStore& pts = solver->points();
    auto* x = pts.view<Vec3>("x");
    auto* failed = pts.view<double>("failed");
    const auto* bid = pts.ints("body");
    int ring = 0;
    for (Index p = 0; p < pts.size(); ++p) {
      if (bid[p] != 1) continue;
      if (x[p][0] < 2e-3) x[p][0] += 0.02;  // the hole's material thrown far out
      else if (x[p][0] < 3e-3) failed[p] = 1.0, ++ring;
    }
    ASSERT_GT(ring, 0);
    const JsonValue h = summary_of_one_sample(sc, *solver).at("holes").at("plate");
    EXPECT_NEAR(h.at("mean_diameter").as_number(), diameter, 1e-12) << "erosion " << erosion;
    EXPECT_NEAR(h.at("entrance_diameter").as_number(), diameter, 1e-12) << "erosion " << erosion;
  }
}

TEST(PenetrationProbe, TunnelEntranceIsWhereTheWallBeginsBelowACrushedFace) {
  // The rock's top 3 mm blown off around the line of flight (thrown far out), except one point in
  // ten between r = 2 and 6 mm left lying as crushed debris, and below it a tunnel of radius 2 mm
  // to 8 mm depth. The entrance is read where the wall begins: 4 mm across at 3 mm depth; the
  // debris (a tenth of the annuli's volume) is not wall.
  const Scenario sc = parse_deck(kLayeredDeck, "layers.yaml");
  auto solver = make_solver(sc);
  FieldStore& pts = solver->points();
  auto* x = pts.view<Vec3>("x");
  const auto* bid = pts.ints("body");
  const double face = 0.02;
  int kept = 0;
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != 0) continue;
    const double depth = face - x[p][1], r = x[p][0];
    if (depth < 3e-3) {
      if (r > 2e-3 && r < 6e-3 && kept++ % 10 == 0) continue;  // debris left lying
      x[p][0] += 0.02;
    } else if (depth < 8e-3 && r < 2e-3) {
      x[p][0] += 0.02;
    }
  }
  const JsonValue out = summary_of_one_sample(sc, *solver);
  const JsonValue& t = out.at("tunnel");
  // Bins of the 1 mm axial cell and annuli of the 1 mm lateral cell: the face and the tunnel's
  // wall lie on their edges.
  EXPECT_NEAR(t.at("depth").as_number(), 8e-3, 1e-12);
  EXPECT_NEAR(t.at("entrance_diameter").as_number(), 4e-3, 1e-12);
  EXPECT_NEAR(t.at("entrance_depth").as_number(), 3e-3, 1e-12);
}

// kDeck's rod, 4 cells across its radius in a band x < 3 mm of 0.25 mm cells, along the flight
// from y = 12 to 30 mm (the target's face at 20 mm: 8 mm deep); graded to 1 mm beyond.
std::string band_deck() {
  std::string deck = kDeck;
  const std::string grid = "cell_size: 1.0e-3}";
  deck.replace(deck.find(grid), grid.size(),
               "cell_size: 1.0e-3, refine: [{axis: x, from: 0, to: 3.0e-3, cell_size: 0.25e-3}, "
               "{axis: y, from: 0.012, to: 0.030, cell_size: 0.25e-3}]}");
  return deck;
}

TEST(PenetrationProbe, ATunnelBeyondTheRefinedBandIsNotResolved) {
  const Scenario sc = parse_deck(band_deck(), "band.yaml");
  auto solver = make_solver(sc);
  FieldStore& pts = solver->points();
  auto* x = pts.view<Vec3>("x");
  const auto* bid = pts.ints("body");
  Index lead = -1;
  for (Index p = 0; p < pts.size() && lead < 0; ++p)
    if (bid[p] == 1) lead = p;
  ASSERT_GE(lead, 0);
  // The tunnel: the target's core (r < 1 mm) moved aside down to the rod point's depth, so that
  // the point drives the tunnel's end (a point far beyond it in intact rock opens no tunnel).
  const auto open_to = [&](double y) {
    for (Index p = 0; p < pts.size(); ++p)
      if (bid[p] == 0 && x[p][0] < 1e-3 && x[p][1] > y) x[p][0] += 0.004;
  };
  // A rod point 7 mm deep: the path to it lies in the band's cells.
  x[lead][1] = 0.013;
  open_to(0.013);
  JsonValue in = summary_of_one_sample(sc, *solver);
  EXPECT_DOUBLE_EQ(in.at("cells_across_radius").as_number(), 4.0);
  // The band's cells are its length over their count, 0.25 mm to the round-off of the node sums.
  EXPECT_NEAR(in.at("path_cells").at("finest").as_number(), 0.25e-3, 1e-17);
  EXPECT_NEAR(in.at("path_cells").at("coarsest").as_number(), 0.25e-3, 1e-17);
  EXPECT_EQ(in.at("path_cells").at("coarser_from_depth").kind(), JsonValue::Kind::Null);
  EXPECT_TRUE(in.at("resolved").as_bool());
  // 14 mm deep: the last 6 mm lie in graded cells, coarser from the band's end at 8 mm deep (the
  // band ends exactly on its node), growing to 1 mm by at most 1.2 per cell (at least 1.2 x 0.25 mm
  // in the first).
  x[lead][1] = 0.006;
  open_to(0.006);
  JsonValue past = summary_of_one_sample(sc, *solver);
  EXPECT_NEAR(past.at("path_cells").at("coarser_from_depth").as_number(), 0.008, 1e-15);
  EXPECT_GT(past.at("path_cells").at("coarsest").as_number(), 0.3e-3);
  EXPECT_LE(past.at("path_cells").at("coarsest").as_number(), 1.0e-3 * (1.0 + 1e-12));
  EXPECT_FALSE(past.at("resolved").as_bool());
}

}  // namespace

}  // namespace test_penetration_probe
