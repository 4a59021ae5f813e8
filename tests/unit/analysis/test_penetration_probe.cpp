// Penetration probe on hand-placed particles: depth of the deepest penetrator particle, cavity
// tip, kinetic energy per segment, and the summary's hydrodynamic values (thesis eq. 3.1-3.2).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/penetration_probe.hpp"
#include "io/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

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

}  // namespace
