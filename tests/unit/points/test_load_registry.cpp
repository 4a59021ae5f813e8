// The load registry: a load kind is one file. A kind defined here (as a new load's file would be)
// is read from a deck with its own keys and range checks, errors at its key's line, and applies
// its force through PointLoads like the built-in kinds; the built-in kinds read as documented
// (gravity as a body force g along the unit direction, confinement as three pressures) and a body
// force applies f = m b exactly (one multiplication per component: compared exactly).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "deck/deck_reader.hpp"
#include "points/load_registry.hpp"
#include "points/point_loads.hpp"
#include "points/point_set.hpp"
#include "run/simulation.hpp"

namespace ballista {
namespace {

/// A kind only this test registers: a force `force` (N) on every point of a body, times the curve.
class UniformForce final : public Load {
 public:
  UniformForce(const LoadSpec& l, const Scenario& sc)
      : force_(l.vectors.at("force")), curve_(l.curve), body_(body_index(sc, l.body)) {}
  void add_forces(const FieldStore& points, double time, LoadForces& out) override {
    const auto* bid = points.ints("body");
    for (Index p = 0; p < points.size(); ++p)
      if (body_ < 0 || bid[p] == body_) out.total[p] += curve_.at(time) * force_;
  }
  std::vector<std::string> history_columns() const override { return {"uniform_fx"}; }
  std::vector<double> history_values() const override { return {force_[0]}; }

 private:
  Vec3 force_;
  LoadCurve curve_;
  int body_;
};

LoadReading read_uniform(LoadEntry& e, LoadSpec load) {
  load.body = e.body(false);
  load.vectors["force"] = e.vector("force");
  if (norm(load.vectors["force"]) > 1e6) e.fail("force", "more than 1 MN per point");
  load.curve = e.curve();
  return {{load}, {}};
}

BALLISTA_REGISTER_LOAD(LoadFactory{
    .name = "test_uniform_force",
    .description = "a force per point (test kind)",
    .read = read_uniform,
    .create = [](const LoadSpec& l, int, const Scenario& sc) -> std::unique_ptr<Load> {
      return std::make_unique<UniformForce>(l, sc);
    }})

std::string deck(const std::string& loads) {
  return R"(
simulation: {solver: mpm, dimension: 3d, end_time: 1.0e-6}
materials:
  steel: {model: linear_elastic, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.3}
grid: {lower: [0, 0, 0], upper: [4.0e-3, 4.0e-3, 4.0e-3], cell_size: 1.0e-3}
bodies:
  - {name: block, material: steel, shape: {type: cylinder, center: [2.0e-3, 2.0e-3, 1.0e-3], radius: 1.0e-3, length: 2.0e-3, axis: z}}
loads:
)" + loads;
}

TEST(LoadRegistry, AKindFromItsOwnFileIsReadAndApplied) {
  const Scenario sc = parse_deck(deck("  - {type: test_uniform_force, force: [1, -2, 3], curve: [[0, 0], [1, 1]]}\n"),
                                 "loads.yaml");
  ASSERT_EQ(sc.loads.size(), 1u);
  EXPECT_EQ(sc.loads[0].type, "test_uniform_force");
  PointSet pts(sc, make_materials(sc), SeedLattice{sc.grid, 0}, 0.0, "");
  PointLoads loads;
  EXPECT_EQ(PointLoads::history_columns(sc), std::vector<std::string>{"uniform_fx"});
  EXPECT_EQ(loads.history_values(sc), std::vector<double>{0.0});  // before the first step
  loads.compute(sc, pts.store(), 0.5);
  ASSERT_EQ(loads.total().size(), static_cast<size_t>(pts.store().size()));
  for (const Vec3& f : loads.total()) {  // curve 0.5 at t = 0.5 s
    EXPECT_EQ(f[0], 0.5);
    EXPECT_EQ(f[1], -1.0);
    EXPECT_EQ(f[2], 1.5);
  }
  EXPECT_EQ(loads.history_values(sc), std::vector<double>{1.0});
}

TEST(LoadRegistry, AKindsOwnCheckAndAnUnknownKindAreDeckErrorsAtTheirKeys) {
  try {
    parse_deck(deck("  - {type: test_uniform_force, force: [2e6, 0, 0]}\n"), "loads.yaml");
    FAIL() << "a kind's own check must stop the deck";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "loads.0.force");
    EXPECT_EQ(e.line(), 9);
  }
  try {
    parse_deck(deck("  - {type: test_uniform_forse, force: [1, 0, 0]}\n"), "loads.yaml");
    FAIL() << "an unknown kind must stop the deck";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "loads.0.type");
    EXPECT_NE(std::string(e.what()).find("test_uniform_force"), std::string::npos) << e.what();
  }
  try {  // keys the kind did not ask for are rejected after it read its entry
    parse_deck(deck("  - {type: test_uniform_force, force: [1, 0, 0], pressure: 3}\n"), "loads.yaml");
    FAIL() << "an unread key must stop the deck";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "loads.0.pressure");
  }
}

TEST(LoadRegistry, BuiltInKindsAreRegistered) {
  for (const char* kind : {"body_force", "gravity", "pressure", "confinement", "indenter", "mms_axis_aligned",
                           "mms_generalized_vortex"}) {
    const LoadFactory* f = find_load(kind);
    ASSERT_NE(f, nullptr) << kind;
    EXPECT_NE(f->read, nullptr) << kind;
  }
  EXPECT_EQ(find_load("no_such_load"), nullptr);
}

// Gravity: b = g d / |d| (EMU seed 001: g = 9.814 m/s^2 by default), applied as f = m b.
TEST(LoadRegistry, GravityIsABodyForceOfGAlongTheUnitDirection) {
  const Scenario sc = parse_deck(deck("  - {type: gravity, direction: [0, 3, -4], g: 10}\n"), "loads.yaml");
  ASSERT_EQ(sc.loads.size(), 1u);
  EXPECT_EQ(sc.loads[0].type, "body_force");
  const Vec3 b = sc.loads[0].vectors.at("acceleration");
  EXPECT_DOUBLE_EQ(b[0], 0.0);
  EXPECT_DOUBLE_EQ(b[1], 6.0);
  EXPECT_DOUBLE_EQ(b[2], -8.0);
  PointSet pts(sc, make_materials(sc), SeedLattice{sc.grid, 0}, 0.0, "");
  PointLoads loads;
  loads.compute(sc, pts.store(), 0.0);
  const auto* m = pts.store().real("mass");
  for (Index p = 0; p < pts.store().size(); ++p) {
    EXPECT_EQ(loads.total()[p][1], m[p] * b[1]);
    EXPECT_EQ(loads.total()[p][2], m[p] * b[2]);
  }
}

// Confinement (thesis seed 000 §5.1): `radial` on the outer surface, `axial` on top and bottom.
TEST(LoadRegistry, ConfinementIsThreePressures) {
  const Scenario sc =
      parse_deck(deck("  - {type: confinement, body: block, radial: 2.0e6, axial: 3.0e6}\n"), "loads.yaml");
  ASSERT_EQ(sc.loads.size(), 3u);
  const char* surfaces[3] = {"outer", "top", "bottom"};
  const double p[3] = {2.0e6, 3.0e6, 3.0e6};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(sc.loads[k].type, "pressure");
    EXPECT_EQ(sc.loads[k].body, "block");
    EXPECT_EQ(sc.loads[k].params.choice("surface"), surfaces[k]);
    EXPECT_EQ(sc.loads[k].params.at("pressure"), p[k]);
  }
}

// A confinement's `hole_radius` is cut in the top face only (where a penetrator enters, thesis
// seed 000 §6.2); a hole as wide as the cylinder, or a hole in a pressure on a side face, is an
// error at its key.
TEST(LoadRegistry, ConfinementHoleIsInTheTopFaceOnly) {
  const Scenario sc =
      parse_deck(deck("  - {type: confinement, body: block, pressure: 1.0e6, hole_radius: 0.5e-3}\n"), "loads.yaml");
  ASSERT_EQ(sc.loads.size(), 3u);
  for (const auto& l : sc.loads)
    EXPECT_EQ(l.params.at("hole_radius"), l.params.choice("surface") == "top" ? 0.5e-3 : 0.0) << l.params.choice("surface");
  try {
    parse_deck(deck("  - {type: confinement, body: block, pressure: 1.0e6, hole_radius: 1.0e-3}\n"), "loads.yaml");
    ADD_FAILURE() << "a hole as wide as the cylinder was accepted";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "loads.0.hole_radius") << e.what();
  }
  try {
    parse_deck(deck("  - {type: pressure, body: block, surface: outer, pressure: 1.0e6, hole_radius: 0.5e-3}\n"),
               "loads.yaml");
    ADD_FAILURE() << "a hole in the outer face was accepted";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "loads.0.hole_radius") << e.what();
    EXPECT_NE(std::string(e.what()).find("top or bottom"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ballista
