// Deck reader: resolution with defaults, validation messages and positions, overrides.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "deck/deck_node.hpp"
#include "deck/deck_reader.hpp"
#include "points/solver_registry.hpp"
#include "support/deck_errors.hpp"

namespace test_deck_reader {

using namespace ballista;
using ballista::test::deck_error;
using ballista::test::parse_error;

namespace {

// A complete 3D deck using most features; defaults are left out on purpose.
const std::string kDeck = R"(simulation:
  end_time: 8.0e-5
  dimension: 3d
mpm:
  update: musl
grid:
  lower: [-0.01, 0, -0.01]
  upper: [0.01, 0.04, 0.01]
  cell_size: 0.5e-3
  boundary: {y_min: wall, x_min: symmetry}
materials:
  copper:
    model: linear_elastic
    density: 8930
    youngs_modulus: 117e9
    poisson_ratio: 0.35
bodies:
  - name: bar
    material: copper
    shape: {type: cylinder, center: [0, 0.001, 0], axis: y, radius: 3.2e-3, length: 32.4e-3}
    velocity: [0, -227, 0]
  - name: plate
    material: copper
    shape: {type: box, lower: [-0.005, 0, -0.005], upper: [0.005, 0.001, 0.005]}
    particles_per_cell: 3
loads:
  - {type: body_force, acceleration: [0, -9.81, 0]}
  - {type: pressure, body: bar, surface: top, pressure: 1e6, curve: [[0, 0], [1e-5, 1]]}
probes:
  - {name: final_length, type: extent, body: bar, axis: y}
  - {name: foot_radius, type: max_radius, body: bar, axis: y, distance: 1e-3}
  - {name: max_eqps, type: field_max, body: bar, field: eqps}
  - {name: ke, type: energy, field: kinetic}
output:
  interval: 1e-5
)";

/// 1-based line of the first occurrence of `needle` in `text` (0 if absent).
int line_of(const std::string& text, const std::string& needle) {
  const size_t pos = text.find(needle);
  if (pos == std::string::npos) return 0;
  int line = 1;
  for (size_t i = 0; i < pos; ++i)
    if (text[i] == '\n') ++line;
  return line;
}

/// kDeck with the first occurrence of `from` replaced by `to`.
std::string deck_with(const std::string& from, const std::string& to, const std::string& base = kDeck) {
  std::string d = base;
  const size_t pos = d.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) d.replace(pos, from.size(), to);
  return d;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

void expect_same_vec(const Vec3& a, const Vec3& b) {
  for (int i = 0; i < 3; ++i) EXPECT_EQ(a[i], b[i]);
}

/// Field-by-field equality of everything except DeckMarks.
void expect_same_scenario(const Scenario& a, const Scenario& b) {
  EXPECT_EQ(a.simulation.solver, b.simulation.solver);
  EXPECT_EQ(a.simulation.dimension, b.simulation.dimension);
  EXPECT_EQ(a.simulation.end_time, b.simulation.end_time);
  EXPECT_EQ(a.simulation.cfl, b.simulation.cfl);
  EXPECT_EQ(a.simulation.max_dt, b.simulation.max_dt);
  EXPECT_EQ(a.simulation.max_steps, b.simulation.max_steps);
  EXPECT_EQ(a.simulation.damping, b.simulation.damping);
  EXPECT_EQ(a.simulation.energy_drift_limit, b.simulation.energy_drift_limit);
  EXPECT_EQ(a.simulation.on_particle_exit, b.simulation.on_particle_exit);
  EXPECT_EQ(a.simulation.threads, b.simulation.threads);
  EXPECT_EQ(a.solver_params.choices.at("shape_function"), b.solver_params.choices.at("shape_function"));
  EXPECT_EQ(a.solver_params.choices.at("update"), b.solver_params.choices.at("update"));
  EXPECT_EQ(a.solver_params.at("flip"), b.solver_params.at("flip"));
  EXPECT_EQ(a.solver_params.at("sort_every"), b.solver_params.at("sort_every"));
  expect_same_vec(a.grid.lower, b.grid.lower);
  expect_same_vec(a.grid.upper, b.grid.upper);
  EXPECT_EQ(a.grid.cell_size, b.grid.cell_size);
  EXPECT_EQ(a.grid.faces, b.grid.faces);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].model, b.materials[i].model);
    ASSERT_EQ(a.materials[i].params.size(), b.materials[i].params.size());
    for (const auto& [k, v] : a.materials[i].params) {
      ASSERT_TRUE(b.materials[i].params.count(k)) << k;
      const double w = b.materials[i].params.at(k);
      if (std::isnan(v))
        EXPECT_TRUE(std::isnan(w)) << k;
      else
        EXPECT_EQ(v, w) << k;
    }
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const BodySpec &x = a.bodies[i], &y = b.bodies[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.material, y.material);
    EXPECT_EQ(x.shape.type, y.shape.type);
    expect_same_vec(x.shape.lower, y.shape.lower);
    expect_same_vec(x.shape.upper, y.shape.upper);
    expect_same_vec(x.shape.center, y.shape.center);
    EXPECT_EQ(x.shape.axis, y.shape.axis);
    EXPECT_EQ(x.shape.radius, y.shape.radius);
    EXPECT_EQ(x.shape.inner_radius, y.shape.inner_radius);
    EXPECT_EQ(x.shape.length, y.shape.length);
    EXPECT_EQ(x.particles_per_cell, y.particles_per_cell);
    expect_same_vec(x.velocity, y.velocity);
    EXPECT_EQ(x.activation_time, y.activation_time);
    EXPECT_EQ(x.initial_state, y.initial_state);
  }
  ASSERT_EQ(a.loads.size(), b.loads.size());
  for (size_t i = 0; i < a.loads.size(); ++i) {
    const LoadSpec &x = a.loads[i], &y = b.loads[i];
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(x.body, y.body);
    EXPECT_EQ(x.vectors.size(), y.vectors.size());
    for (const auto& [key, v] : x.vectors) expect_same_vec(v, y.vectors.at(key));
    EXPECT_EQ(x.params.choices, y.params.choices);
    using Numbers = std::map<std::string, double>;
    EXPECT_EQ(static_cast<const Numbers&>(x.params), static_cast<const Numbers&>(y.params));
    EXPECT_EQ(x.curve.t, y.curve.t);
    EXPECT_EQ(x.curve.v, y.curve.v);
  }
  ASSERT_EQ(a.probes.size(), b.probes.size());
  for (size_t i = 0; i < a.probes.size(); ++i) {
    const ProbeSpec &x = a.probes[i], &y = b.probes[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.type, y.type);
    using Numbers = std::map<std::string, double>;  // ParamValues' numbers, without its choices
    EXPECT_EQ(static_cast<const Numbers&>(x.params), static_cast<const Numbers&>(y.params));
    EXPECT_EQ(x.params.choices, y.params.choices);
    ASSERT_EQ(x.vectors.size(), y.vectors.size());
    for (const auto& [key, v] : x.vectors) expect_same_vec(v, y.vectors.at(key));
  }
  EXPECT_EQ(a.output.interval, b.output.interval);
  EXPECT_EQ(a.output.fields, b.output.fields);
  EXPECT_EQ(a.output.domains, b.output.domains);
  EXPECT_EQ(a.output.history_every, b.output.history_every);
}

}  // namespace

// ---- a valid deck ----------------------------------------------------------------------------

TEST(DeckReader, ValidDeckResolvesWithDefaults) {
  const Scenario s = parse_deck(kDeck, "taylor.yaml");
  EXPECT_EQ(s.file, "taylor.yaml");
  // simulation: given and defaulted
  EXPECT_EQ(s.simulation.solver, "mpm");
  EXPECT_EQ(s.simulation.dimension, Dimension::ThreeD);
  EXPECT_DOUBLE_EQ(s.simulation.end_time, 8.0e-5);
  EXPECT_DOUBLE_EQ(s.simulation.cfl, 0.3);
  EXPECT_EQ(s.simulation.max_dt, 0.0);
  EXPECT_EQ(s.simulation.max_steps, 0);
  EXPECT_EQ(s.simulation.on_particle_exit, "stop");
  EXPECT_EQ(s.simulation.threads, 0);
  // mpm
  EXPECT_EQ(s.solver_params.choices.at("shape_function"), "linear");
  EXPECT_EQ(s.solver_params.choices.at("update"), "musl");
  EXPECT_EQ(s.solver_params.at("flip"), 1.0);
  EXPECT_EQ(s.solver_params.at("sort_every"), 20);
  // grid
  EXPECT_EQ(s.grid.lower[0], -0.01);
  EXPECT_EQ(s.grid.upper[1], 0.04);
  EXPECT_EQ(s.grid.cell_size, 0.5e-3);
  EXPECT_EQ(s.grid.faces[0], FaceBC::Symmetry);  // x_min
  EXPECT_EQ(s.grid.faces[1], FaceBC::Free);      // x_max defaulted
  EXPECT_EQ(s.grid.faces[2], FaceBC::Wall);      // y_min
  EXPECT_EQ(s.grid.faces[5], FaceBC::Free);
  // materials: every ParamSpec present, absent optional ones NaN
  ASSERT_EQ(s.materials.size(), 1u);
  const MaterialSpec& cu = s.materials[0];
  EXPECT_EQ(cu.name, "copper");
  EXPECT_EQ(cu.model, "linear_elastic");
  EXPECT_EQ(cu.params.at("density"), 8930.0);
  EXPECT_EQ(cu.params.at("youngs_modulus"), 117e9);
  EXPECT_EQ(cu.params.at("poisson_ratio"), 0.35);
  EXPECT_TRUE(std::isnan(cu.params.at("bulk_modulus")));
  EXPECT_TRUE(std::isnan(cu.params.at("shear_modulus")));
  EXPECT_EQ(cu.mark.line, line_of(kDeck, "copper:"));
  EXPECT_EQ(cu.mark.key_path, "materials.copper");
  EXPECT_EQ(cu.param_marks.at("poisson_ratio").line, line_of(kDeck, "poisson_ratio:"));
  EXPECT_EQ(cu.param_marks.count("bulk_modulus"), 0u);
  // bodies
  ASSERT_EQ(s.bodies.size(), 2u);
  const BodySpec& bar = s.bodies[0];
  EXPECT_EQ(bar.name, "bar");
  EXPECT_EQ(bar.material, "copper");
  EXPECT_EQ(bar.shape.type, "cylinder");
  EXPECT_EQ(bar.shape.axis, 1);
  EXPECT_EQ(bar.shape.radius, 3.2e-3);
  EXPECT_EQ(bar.shape.length, 32.4e-3);
  EXPECT_EQ(bar.shape.center[1], 0.001);
  EXPECT_EQ(bar.velocity[1], -227.0);
  EXPECT_EQ(bar.particles_per_cell, 2);
  EXPECT_EQ(bar.activation_time, 0.0);
  EXPECT_EQ(bar.initial_state, "none");
  EXPECT_EQ(bar.mark.key_path, "bodies.0");
  EXPECT_EQ(bar.mark.line, line_of(kDeck, "- name: bar"));
  EXPECT_EQ(s.bodies[1].particles_per_cell, 3);
  EXPECT_EQ(s.bodies[1].shape.upper[1], 0.001);
  expect_same_vec(s.bodies[1].velocity, Vec3{});
  // loads
  ASSERT_EQ(s.loads.size(), 2u);
  EXPECT_EQ(s.loads[0].type, "body_force");
  EXPECT_EQ(s.loads[0].body, "");
  EXPECT_EQ(s.loads[0].vectors.at("acceleration")[1], -9.81);
  EXPECT_TRUE(s.loads[0].curve.t.empty());
  EXPECT_EQ(s.loads[1].params.choice("surface"), "top");
  EXPECT_EQ(s.loads[1].params.at("pressure"), 1e6);
  ASSERT_EQ(s.loads[1].curve.t.size(), 2u);
  EXPECT_EQ(s.loads[1].curve.t[1], 1e-5);
  EXPECT_EQ(s.loads[1].curve.v[1], 1.0);
  EXPECT_DOUBLE_EQ(s.loads[1].curve.at(0.5e-5), 0.5);
  EXPECT_EQ(s.loads[1].mark.line, line_of(kDeck, "{type: pressure"));
  // probes
  ASSERT_EQ(s.probes.size(), 4u);
  EXPECT_EQ(s.probes[0].params.at("axis"), 1);
  EXPECT_EQ(s.probes[1].type, "max_radius");
  EXPECT_EQ(s.probes[1].params.at("distance"), 1e-3);
  EXPECT_EQ(s.probes[1].params.at("plane"), 0.0);
  EXPECT_EQ(s.probes[2].params.choice("field"), "eqps");
  EXPECT_EQ(s.probes[3].params.choice("field"), "kinetic");
  EXPECT_EQ(s.probes[3].params.choice("body"), "");
  // output
  EXPECT_EQ(s.output.interval, 1e-5);
  EXPECT_TRUE(s.output.fields.empty());
  EXPECT_FALSE(s.output.domains);
  EXPECT_EQ(s.output.history_every, 10);
}

TEST(DeckReader, ResolvedYamlHasEveryDefaultAndReparsesToTheSameScenario) {
  const Scenario s = parse_deck(kDeck, "taylor.yaml");
  const std::string& r = s.resolved_yaml;
  for (const char* key : {"solver: mpm", "cfl: 0.3", "max_dt: 0", "max_steps: 0", "on_particle_exit: stop",
                          "shape_function: linear", "flip: 1", "sort_every: 20", "x_max: free", "z_min: free",
                          "bulk_modulus: ~", "particles_per_cell: 2", "activation_time: 0", "initial_state: none",
                          "velocity: [0, 0, 0]", "curve: []", "plane: 0", "center: [0, 0, 0]", "fields: []",
                          "domains: false", "history_every: 10", "end_time: 8e-05", "youngs_modulus: 1.17e+11"})
    EXPECT_TRUE(contains(r, key)) << "missing '" << key << "' in\n" << r;
  const Scenario again = parse_deck(r, "resolved.yaml");
  expect_same_scenario(s, again);
  // Resolving is idempotent.
  const Scenario third = parse_deck(again.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(third.resolved_yaml.substr(third.resolved_yaml.find('\n')),
            again.resolved_yaml.substr(again.resolved_yaml.find('\n')));
}

TEST(DeckReader, ReadsFromFileAndReportsMissingFile) {
  const std::string path = testing::TempDir() + "deck_reader_test.yaml";
  {
    std::ofstream out(path);
    out << kDeck;
  }
  const Scenario s = read_deck(path, {"simulation.cfl=0.2"});
  EXPECT_EQ(s.file, path);
  EXPECT_EQ(s.simulation.cfl, 0.2);
  std::remove(path.c_str());
  const DeckError e = deck_error([&] { read_deck(path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_EQ(e.line(), 0);
  EXPECT_TRUE(contains(e.what(), "cannot open")) << e.what();
}

// ---- unknown and missing keys ----------------------------------------------------------------

TEST(DeckReader, TypoKeyGivesLineAndSuggestion) {
  const std::string d = deck_with("youngs_modulus: 117e9", "youngs_modulos: 117e9");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.line(), line_of(d, "youngs_modulos"));
  EXPECT_EQ(e.line(), 15);
  EXPECT_EQ(e.column(), 5);
  EXPECT_EQ(e.key_path(), "materials.copper.youngs_modulos");
  EXPECT_TRUE(contains(e.what(), "unknown key 'youngs_modulos' in materials.copper; did you mean 'youngs_modulus'?"))
      << e.what();
  EXPECT_TRUE(contains(e.what(), "deck.yaml:15:5:")) << e.what();
}

TEST(DeckReader, TypoInRequiredKeyIsReportedAsTypoNotAsMissing) {
  const std::string d = deck_with("end_time: 8.0e-5", "end_tme: 8.0e-5");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.key_path(), "simulation.end_tme");
  EXPECT_TRUE(contains(e.what(), "did you mean 'end_time'?")) << e.what();
}

TEST(DeckReader, UnknownSectionAndUnrelatedKeyListValidNames) {
  const std::string d = deck_with("output:", "outptu:");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.line(), line_of(d, "outptu:"));
  EXPECT_TRUE(contains(e.what(), "did you mean 'output'?")) << e.what();

  // A key valid elsewhere but not for this probe type: no close name, so list the valid ones.
  const std::string d2 = deck_with("{name: final_length, type: extent, body: bar, axis: y}",
                                   "{name: final_length, type: extent, body: bar, axis: y, distance: 1}");
  const DeckError e2 = parse_error(d2);
  EXPECT_EQ(e2.key_path(), "probes.0.distance");
  EXPECT_EQ(e2.line(), line_of(d2, "final_length"));
  EXPECT_TRUE(contains(e2.what(), "expected one of: name, type, body, axis")) << e2.what();
}

TEST(DeckReader, MissingRequiredKey) {
  const std::string d = deck_with("  cell_size: 0.5e-3\n", "");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "grid.cell_size");
  EXPECT_EQ(e.line(), line_of(d, "grid:"));
  EXPECT_TRUE(contains(e.what(), "missing required key 'cell_size' in grid (expected a number > 0 (m))")) << e.what();

  const DeckError e2 = parse_error(deck_with("    material: copper\n", ""));
  EXPECT_EQ(e2.key_path(), "bodies.0.material");
  EXPECT_EQ(e2.line(), line_of(kDeck, "- name: bar"));

  const DeckError e3 = parse_error("simulation: {end_time: 1}\n");
  EXPECT_EQ(e3.key_path(), "grid");
  EXPECT_TRUE(contains(e3.what(), "missing required key 'grid'")) << e3.what();
}

TEST(DeckReader, DuplicateKeysAndNames) {
  const std::string d = deck_with("    density: 8930\n", "    density: 8930\n    density: 8000\n");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.line(), line_of(d, "density: 8000"));
  EXPECT_TRUE(contains(e.what(), "duplicate key 'density'")) << e.what();

  const std::string d2 = deck_with("- name: plate", "- name: bar");
  const DeckError e2 = parse_error(d2);
  EXPECT_EQ(e2.key_path(), "bodies.1.name");
  EXPECT_EQ(e2.line(), 22);
  EXPECT_TRUE(contains(e2.what(), "duplicate body name 'bar' (also bodies.0 at line 18)")) << e2.what();

  const std::string d4 = deck_with("bodies:", "  copper: {model: linear_elastic, density: 1, bulk_modulus: 1, shear_modulus: 1}\nbodies:");
  const DeckError e4 = parse_error(d4);
  EXPECT_EQ(e4.key_path(), "materials.copper");
  EXPECT_EQ(e4.line(), 17);
  EXPECT_TRUE(contains(e4.what(), "duplicate name 'copper' in materials")) << e4.what();

  const std::string d3 = deck_with("{name: ke,", "{name: max_eqps,");
  const DeckError e3 = parse_error(d3);
  EXPECT_EQ(e3.key_path(), "probes.3.name");
  EXPECT_TRUE(contains(e3.what(), "duplicate probe name 'max_eqps'")) << e3.what();
}

// ---- types and ranges ------------------------------------------------------------------------

TEST(DeckReader, WrongTypes) {
  const DeckError e = parse_error(deck_with("end_time: 8.0e-5", "end_time: fast"));
  EXPECT_EQ(e.key_path(), "simulation.end_time");
  EXPECT_EQ(e.line(), 2);
  EXPECT_EQ(e.column(), 13);
  EXPECT_TRUE(contains(e.what(), "expected a number > 0 (s), got 'fast'")) << e.what();

  const DeckError e2 = parse_error(deck_with("velocity: [0, -227, 0]", "velocity: [0, -227]"));
  EXPECT_EQ(e2.key_path(), "bodies.0.velocity");
  EXPECT_TRUE(contains(e2.what(), "expected a list of 3 numbers, got a list of 2")) << e2.what();

  const DeckError e3 = parse_error(deck_with("velocity: [0, -227, 0]", "velocity: [0, fast, 0]"));
  EXPECT_EQ(e3.key_path(), "bodies.0.velocity.1");
  EXPECT_TRUE(contains(e3.what(), "expected a number, got 'fast'")) << e3.what();

  const DeckError e4 = parse_error(deck_with("particles_per_cell: 3", "particles_per_cell: 2.5"));
  EXPECT_TRUE(contains(e4.what(), "expected an integer in 1..8, got '2.5'")) << e4.what();

  const DeckError e5 = parse_error(deck_with("interval: 1e-5", "interval: 1e-5\n  domains: maybe"));
  EXPECT_EQ(e5.key_path(), "output.domains");
  EXPECT_TRUE(contains(e5.what(), "expected true or false, got 'maybe'")) << e5.what();

  const DeckError e6 = parse_error(deck_with("density: 8930", "density: '8930'"));
  EXPECT_TRUE(contains(e6.what(), "expected a number > 0 (kg/m^3), got '8930'")) << e6.what();

  const DeckError e7 = parse_error(deck_with("  update: musl", "  - update: musl"));
  EXPECT_EQ(e7.key_path(), "mpm");
  EXPECT_TRUE(contains(e7.what(), "expected a map, got a list")) << e7.what();
}

TEST(DeckReader, PoissonRatioOutOfRangeNamesKeyPathAndLine) {
  const std::string d = deck_with("poisson_ratio: 0.35", "poisson_ratio: 0.6");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "materials.copper.poisson_ratio");
  EXPECT_EQ(e.line(), 16);
  EXPECT_EQ(e.column(), 20);
  EXPECT_TRUE(contains(e.what(), "expected a number in (-1, 0.5), got 0.6")) << e.what();
  EXPECT_TRUE(contains(e.what(), "'materials.copper.poisson_ratio'")) << e.what();

  const DeckError e2 = parse_error(deck_with("density: 8930", "density: -1"));
  EXPECT_TRUE(contains(e2.what(), "expected a number > 0 (kg/m^3), got -1")) << e2.what();
}

TEST(DeckReader, RangesOfSimulationGridAndBodies) {
  struct Case {
    std::string from, to, key_path, message;
  };
  const std::vector<Case> cases{
      {"end_time: 8.0e-5", "end_time: 0", "simulation.end_time", "expected a number > 0 (s), got 0"},
      {"dimension: 3d", "dimension: 3d\n  cfl: 1.5", "simulation.cfl", "expected a number in (0, 1], got 1.5"},
      {"dimension: 3d", "dimension: 3d\n  cfl: 0", "simulation.cfl", "expected a number in (0, 1], got 0"},
      {"update: musl", "update: musl\n  flip: -0.1", "mpm.flip", "expected a number in [0, 1], got -0.1"},
      {"particles_per_cell: 3", "particles_per_cell: 9", "bodies.1.particles_per_cell",
       "expected an integer in 1..8, got 9"},
      {"particles_per_cell: 3", "particles_per_cell: 0", "bodies.1.particles_per_cell",
       "expected an integer in 1..8, got 0"},
      {"cell_size: 0.5e-3", "cell_size: -0.5e-3", "grid.cell_size", "expected a number > 0 (m), got -5e-04"},
      {"upper: [0.01, 0.04, 0.01]", "upper: [0.01, 0, 0.01]", "grid.upper",
       "in y upper is 0 and lower 0"},
      {"radius: 3.2e-3", "radius: 0", "bodies.0.shape.radius", "expected a number > 0 (m), got 0"},
      {"upper: [0.005, 0.001, 0.005]", "upper: [0.005, 0.001, -0.006]", "bodies.1.shape.upper",
       "in z upper is -0.006 and lower -0.005"},
      {"interval: 1e-5", "interval: -1", "output.interval", "expected a number >= 0 (s), got -1"},
      {"interval: 1e-5", "history_every: 0", "output.history_every", "expected an integer >= 1, got 0"},
      {"distance: 1e-3", "distance: 0", "probes.1.distance", "expected a number > 0 (m), got 0"},
  };
  for (const auto& c : cases) {
    const std::string d = deck_with(c.from, c.to);
    const DeckError e = parse_error(d);
    EXPECT_EQ(e.key_path(), c.key_path) << c.to;
    EXPECT_TRUE(contains(e.what(), c.message)) << c.to << " -> " << e.what();
    EXPECT_GT(e.line(), 0) << c.to;
  }
}

TEST(DeckReader, EnumValuesListTheValidOnes) {
  const std::string d = deck_with("update: musl", "shape_function: gimpp");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "mpm.shape_function");
  EXPECT_EQ(e.line(), 5);
  EXPECT_TRUE(contains(e.what(), "expected one of: linear, gimp, cpdi, bspline3, got 'gimpp' (did you mean 'gimp'?)"))
      << e.what();

  const DeckError e2 = parse_error(deck_with("x_min: symmetry", "x_min: slip"));
  EXPECT_EQ(e2.key_path(), "grid.boundary.x_min");
  EXPECT_TRUE(contains(e2.what(), "expected one of: free, fixed, symmetry, wall, got 'slip'")) << e2.what();

  const DeckError e3 = parse_error(deck_with("field: kinetic", "field: potential"));
  EXPECT_EQ(e3.key_path(), "probes.3.field");
  EXPECT_TRUE(contains(e3.what(), "kinetic, internal, plastic, external, total")) << e3.what();
}

// ---- materials -------------------------------------------------------------------------------

TEST(DeckReader, UnknownModelListsRegisteredNames) {
  const std::string d = deck_with("model: linear_elastic", "model: linear_elastc");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "materials.copper.model");
  EXPECT_EQ(e.line(), 13);
  EXPECT_TRUE(contains(e.what(), "unknown material model 'linear_elastc'; did you mean 'linear_elastic'?"))
      << e.what();
  EXPECT_TRUE(contains(e.what(), "registered models: ")) << e.what();
  EXPECT_TRUE(contains(e.what(), "linear_elastic")) << e.what();

  const DeckError e2 = parse_error(deck_with("model: linear_elastic", "model: foam"));
  std::string all;
  for (const auto& f : material_registry()) all += (all.empty() ? "" : ", ") + f.model;
  EXPECT_TRUE(contains(e2.what(), "(registered models: " + all + ")")) << e2.what();

  const DeckError e3 = parse_error(deck_with("    model: linear_elastic\n", ""));
  EXPECT_EQ(e3.key_path(), "materials.copper.model");
  EXPECT_EQ(e3.line(), line_of(kDeck, "copper:"));
}

// The solver and its section come from the solver registry (points/solver_registry.hpp).
TEST(DeckReader, SolverAndItsSectionComeFromTheRegistry) {
  const DeckError e = parse_error(deck_with("  dimension: 3d\n", "  dimension: 3d\n  solver: peridynamic\n"));
  EXPECT_EQ(e.key_path(), "simulation.solver");
  std::string all;
  for (const auto& f : solver_registry()) all += (all.empty() ? "" : ", ") + f.name;
  EXPECT_TRUE(contains(e.what(), "expected one of: " + all)) << e.what();
  // The section's parameters are typed by their specs: sort_every is an integer.
  const DeckError e2 = parse_error(deck_with("  update: musl\n", "  update: musl\n  sort_every: 2.5\n"));
  EXPECT_EQ(e2.key_path(), "mpm.sort_every");
  const Scenario s = parse_deck(deck_with("  update: musl\n", "  update: usl\n  shape_function: gimp\n"), "d.yaml");
  EXPECT_EQ(s.solver_params.choices.at("update"), "usl");
  EXPECT_EQ(s.solver_params.choices.at("shape_function"), "gimp");
  EXPECT_EQ(s.solver_params.at("sort_every"), 20.0);
}

TEST(DeckReader, UnknownMaterialParameterSuggestsClosest) {
  const std::string d = deck_with("density: 8930", "density: 8930\n    shear_modulu: 4e10");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "materials.copper.shear_modulu");
  EXPECT_EQ(e.line(), line_of(d, "shear_modulu"));
  EXPECT_TRUE(contains(e.what(), "did you mean 'shear_modulus'?")) << e.what();
}

TEST(DeckReader, ParamErrorFromMakeMapsToTheParameterLine) {
  // Both pairs of elastic constants: make() blames bulk_modulus, which is on its own line.
  const std::string d = deck_with("    poisson_ratio: 0.35\n", "    poisson_ratio: 0.35\n    bulk_modulus: 1.4e11\n");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "materials.copper.bulk_modulus");
  EXPECT_EQ(e.line(), line_of(d, "bulk_modulus"));
  EXPECT_EQ(e.line(), 17);
  EXPECT_TRUE(contains(e.what(), "material 'copper' (linear_elastic): give either youngs_modulus and poisson_ratio"))
      << e.what();

  // poisson_ratio absent: make() blames it; it is not in the deck, so the material's line is used.
  const std::string d2 = deck_with("    poisson_ratio: 0.35\n", "");
  const DeckError e2 = parse_error(d2);
  EXPECT_EQ(e2.key_path(), "materials.copper.poisson_ratio");
  EXPECT_EQ(e2.line(), line_of(d2, "copper:"));
  EXPECT_EQ(e2.line(), 12);
  EXPECT_TRUE(contains(e2.what(), "youngs_modulus needs poisson_ratio")) << e2.what();
}

TEST(DeckReader, ElasticConstantsAsBulkAndShear) {
  const std::string d = deck_with("    youngs_modulus: 117e9\n    poisson_ratio: 0.35\n",
                                  "    bulk_modulus: 1.3e11\n    shear_modulus: 4.3e10\n");
  const Scenario s = parse_deck(d, "deck.yaml");
  EXPECT_EQ(s.materials[0].params.at("bulk_modulus"), 1.3e11);
  EXPECT_TRUE(std::isnan(s.materials[0].params.at("youngs_modulus")));
  EXPECT_TRUE(contains(s.resolved_yaml, "youngs_modulus: ~"));
  EXPECT_TRUE(contains(s.resolved_yaml, "shear_modulus: 4.3e+10"));
}

// ---- references ------------------------------------------------------------------------------

TEST(DeckReader, UnknownReferences) {
  const std::string d = deck_with("material: copper", "material: coper");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "bodies.0.material");
  EXPECT_EQ(e.line(), 19);
  EXPECT_TRUE(contains(e.what(), "unknown material 'coper'; did you mean 'copper'?")) << e.what();

  const DeckError e2 = parse_error(deck_with("body: bar, surface", "body: rod, surface"));
  EXPECT_EQ(e2.key_path(), "loads.1.body");
  EXPECT_TRUE(contains(e2.what(), "unknown body 'rod'; expected one of: bar, plate")) << e2.what();

  const DeckError e3 = parse_error(deck_with("type: extent, body: bar", "type: extent, body: plat"));
  EXPECT_EQ(e3.key_path(), "probes.0.body");
  EXPECT_TRUE(contains(e3.what(), "did you mean 'plate'?")) << e3.what();

  const DeckError e4 = parse_error(deck_with("surface: top", "surface: inner"));
  EXPECT_EQ(e4.key_path(), "loads.1.surface");
  EXPECT_TRUE(contains(e4.what(), "expected one of: outer, top, bottom (the surfaces of body 'bar', a cylinder)"))
      << e4.what();
}

TEST(DeckReader, LoadCurveMustIncrease) {
  const std::string d = deck_with("curve: [[0, 0], [1e-5, 1]]", "curve: [[0, 0], [1e-5, 1], [1e-5, 2]]");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "loads.1.curve.2.0");
  EXPECT_TRUE(contains(e.what(), "strictly increasing; 1e-05 follows 1e-05")) << e.what();
  const DeckError e2 = parse_error(deck_with("curve: [[0, 0], [1e-5, 1]]", "curve: [[0, 0, 1]]"));
  EXPECT_EQ(e2.key_path(), "loads.1.curve.0");
  EXPECT_TRUE(contains(e2.what(), "expected a [time, scale] pair")) << e2.what();
}

// ---- 2D decks --------------------------------------------------------------------------------

TEST(DeckReader, AxisymmetricDeck) {
  const std::string axi = R"(simulation: {end_time: 8e-5, dimension: axisymmetric}
grid: {lower: [0, 0], upper: [0.01, 0.036], cell_size: 0.4e-3, boundary: {x_min: symmetry, y_min: wall}}
materials:
  copper: {model: linear_elastic, density: 8930, youngs_modulus: 117e9, poisson_ratio: 0.35}
bodies:
  - {name: bar, material: copper, velocity: [0, -227],
     shape: {type: cylinder, center: [0, 0], axis: y, radius: 3.2e-3, length: 32.4e-3}}
probes:
  - {name: foot_radius, type: max_radius, body: bar, axis: y, distance: 1e-3}
)";
  const Scenario s = parse_deck(axi, "axi.yaml");
  EXPECT_EQ(s.simulation.dimension, Dimension::Axisymmetric);
  EXPECT_EQ(s.grid.upper[1], 0.036);
  EXPECT_EQ(s.grid.upper[2], 0.0);
  EXPECT_EQ(s.bodies[0].velocity[1], -227.0);
  EXPECT_TRUE(contains(s.resolved_yaml, "upper: [0.01, 0.036, 0]")) << s.resolved_yaml;
  expect_same_scenario(s, parse_deck(s.resolved_yaml, "resolved.yaml"));

  const DeckError e = parse_error(deck_with("axis: y, radius", "axis: z, radius", axi));
  EXPECT_EQ(e.key_path(), "bodies.0.shape.axis");
  EXPECT_EQ(e.line(), 7);
  EXPECT_TRUE(contains(e.what(), "expected axis y in an axisymmetric deck")) << e.what();

  const DeckError e2 = parse_error(deck_with("center: [0, 0]", "center: [0.001, 0]", axi));
  EXPECT_EQ(e2.key_path(), "bodies.0.shape.center");
  EXPECT_TRUE(contains(e2.what(), "expected x = 0")) << e2.what();

  const DeckError e3 = parse_error(deck_with("axis: y, distance", "axis: z, distance", axi));
  EXPECT_EQ(e3.key_path(), "probes.0.axis");
  EXPECT_TRUE(contains(e3.what(), "expected one of: x, y, got 'z'")) << e3.what();
}

TEST(DeckReader, PlaneStrainDiskNeedsNoLength) {
  const std::string ps = R"(simulation: {end_time: 1e-4, dimension: plane_strain}
grid: {lower: [-0.02, -0.02], upper: [0.02, 0.02], cell_size: 1e-3}
materials:
  steel: {model: linear_elastic, density: 7800, bulk_modulus: 160e9, shear_modulus: 80e9}
bodies:
  - {name: ring, material: steel, shape: {type: tube, center: [0, 0], axis: z, radius: 0.01, inner_radius: 0.005}}
loads:
  - {type: pressure, body: ring, surface: inner, pressure: 1e8}
)";
  const Scenario s = parse_deck(ps, "ring.yaml");
  EXPECT_EQ(s.bodies[0].shape.type, "tube");
  EXPECT_EQ(s.bodies[0].shape.axis, 2);
  EXPECT_EQ(s.bodies[0].shape.length, 0.0);
  EXPECT_EQ(s.bodies[0].shape.inner_radius, 0.005);
  EXPECT_EQ(s.loads[0].params.choice("surface"), "inner");
  const DeckError e = parse_error(deck_with("surface: inner", "surface: top", ps));
  EXPECT_TRUE(contains(e.what(), "expected one of: outer, inner (the surfaces of body 'ring', a tube)")) << e.what();
  const DeckError e2 = parse_error(deck_with("inner_radius: 0.005", "inner_radius: 0.01", ps));
  EXPECT_EQ(e2.key_path(), "bodies.0.shape.inner_radius");
  EXPECT_TRUE(contains(e2.what(), "expected inner_radius < radius")) << e2.what();
}

TEST(DeckReader, BodyOutsideTheGridIsRejected) {
  const std::string d = deck_with("center: [0, 0.001, 0]", "center: [0, 0.05, 0]");
  const DeckError e = parse_error(d);
  EXPECT_EQ(e.key_path(), "bodies.0.shape");
  EXPECT_TRUE(contains(e.what(), "body 'bar' lies entirely outside the grid (in y")) << e.what();
}

// ---- overrides -------------------------------------------------------------------------------

TEST(DeckOverrides, SetNestedValues) {
  const Scenario s = parse_deck(kDeck, "deck.yaml",
                                {"bodies.0.velocity=[0,-100,0]", "materials.copper.density=9000",
                                 "simulation.cfl = 0.25", "grid.boundary.z_max=fixed", "output.fields=[stress, eqps]",
                                 "loads.1.curve=[[0, 1]]"});
  EXPECT_EQ(s.bodies[0].velocity[1], -100.0);
  EXPECT_EQ(s.materials[0].params.at("density"), 9000.0);
  EXPECT_EQ(s.simulation.cfl, 0.25);
  EXPECT_EQ(s.grid.faces[5], FaceBC::Fixed);
  EXPECT_EQ(s.output.fields, (std::vector<std::string>{"stress", "eqps"}));
  EXPECT_EQ(s.loads[1].curve.t.size(), 1u);
  EXPECT_TRUE(contains(s.resolved_yaml, "velocity: [0, -100, 0]"));
  EXPECT_TRUE(contains(s.resolved_yaml, "density: 9000"));
  // Marks of overridden values have no line.
  EXPECT_EQ(s.materials[0].param_marks.at("density").line, 0);
  EXPECT_EQ(s.materials[0].param_marks.at("youngs_modulus").line, 15);
}

TEST(DeckOverrides, CreateMissingSectionsAndKeys) {
  const std::string d = deck_with("mpm:\n  update: musl\n", "");
  const Scenario s = parse_deck(d, "deck.yaml", {"mpm.flip=0.5", "simulation.max_steps=100"});
  EXPECT_EQ(s.solver_params.at("flip"), 0.5);
  EXPECT_EQ(s.solver_params.choices.at("update"), "musl");  // the default, filled in the section the override created
  EXPECT_EQ(s.simulation.max_steps, 100);

  // A required key missing from a section that only an override created.
  const std::string no_grid = deck_with("grid:\n  lower: [-0.01, 0, -0.01]\n  upper: [0.01, 0.04, 0.01]\n  cell_size: 0.5e-3\n  boundary: {y_min: wall, x_min: symmetry}\n", "");
  const DeckError e = parse_error(no_grid, {"grid.boundary.x_min=fixed"});
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.key_path(), "grid.lower");
  EXPECT_TRUE(contains(e.what(), "missing required key 'lower' in grid (expected a list of 3 numbers) (section created by override 'grid.boundary.x_min=fixed')"))
      << e.what();
}

TEST(DeckOverrides, BadPathsFailNamingTheOverride) {
  const DeckError e = parse_error(kDeck, {"bodies.5.velocity=[0,-100,0]"});
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.key_path(), "bodies.5.velocity");
  EXPECT_TRUE(contains(e.what(), "in override 'bodies.5.velocity=[0,-100,0]': index 5 is out of range: 'bodies' has 2 elements"))
      << e.what();

  const DeckError e2 = parse_error(kDeck, {"bodies.bar.velocity=[0,-100,0]"});
  EXPECT_TRUE(contains(e2.what(), "'bodies' is a list, so 'bar' must be an element index (0..1)")) << e2.what();

  const DeckError e3 = parse_error(kDeck, {"simulation.end_time.value=3"});
  EXPECT_TRUE(contains(e3.what(), "'simulation.end_time' is a single value, so it has no entry 'value'")) << e3.what();

  const DeckError e4 = parse_error(kDeck, {"simulation.cfl"});
  EXPECT_TRUE(contains(e4.what(), "in override 'simulation.cfl': expected key.path=value")) << e4.what();

  const DeckError e5 = parse_error(kDeck, {"simulation..cfl=1"});
  EXPECT_TRUE(contains(e5.what(), "empty component")) << e5.what();

  const DeckError e6 = parse_error(kDeck, {"bodies.0.velocity=[0,"});
  EXPECT_TRUE(contains(e6.what(), "is not valid YAML")) << e6.what();
}

TEST(DeckOverrides, ValidationErrorsInOverriddenValuesNameTheOverride) {
  // A misspelt key created by an override.
  const DeckError e = parse_error(kDeck, {"materials.copper.youngs_modulos=1e9"});
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.key_path(), "materials.copper.youngs_modulos");
  EXPECT_TRUE(contains(e.what(), "did you mean 'youngs_modulus'? (value from override 'materials.copper.youngs_modulos=1e9')"))
      << e.what();
  // A bad value.
  const DeckError e2 = parse_error(kDeck, {"materials.copper.poisson_ratio=0.7"});
  EXPECT_EQ(e2.line(), 0);
  EXPECT_TRUE(contains(e2.what(), "expected a number in (-1, 0.5), got 0.7 (value from override")) << e2.what();
  // Inside a structured value.
  const DeckError e3 = parse_error(kDeck, {"bodies.1.shape={type: sphere, center: [0, 0.01, 0]}"});
  EXPECT_EQ(e3.key_path(), "bodies.1.shape.radius");
  EXPECT_TRUE(contains(e3.what(), "missing required key 'radius'")) << e3.what();
  EXPECT_TRUE(contains(e3.what(), "(value from override 'bodies.1.shape=")) << e3.what();
}

// ---- YAML syntax and helpers -----------------------------------------------------------------

TEST(DeckReader, YamlSyntaxErrorHasPosition) {
  const DeckError e = parse_error("simulation:\n  end_time: [1, 2\ngrid: {}\n");
  EXPECT_GT(e.line(), 0);
  EXPECT_TRUE(contains(e.what(), "invalid YAML")) << e.what();
  const DeckError e2 = parse_error("- a\n- b\n");
  EXPECT_EQ(e2.line(), 1);
  EXPECT_TRUE(contains(e2.what(), "expected the deck to be a map")) << e2.what();
}

TEST(DeckNames, EditDistanceAndSuggestions) {
  EXPECT_EQ(edit_distance("youngs_modulos", "youngs_modulus"), 1u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(closest_name("cfll", {"cfl", "flip", "end_time"}), "cfl");
  EXPECT_EQ(closest_name("plane", {"name", "type", "body", "axis"}), "");
  EXPECT_EQ(suggest("plane", {"name", "type"}), "; expected one of: name, type");
  EXPECT_EQ(format_number(0.3), "0.3");
  EXPECT_EQ(format_number(8e-5), "8e-05");
  EXPECT_EQ(format_number(-227), "-227");
  EXPECT_EQ(NumberRange::between(-1, 0.5, true, true).describe(), "in (-1, 0.5)");
  EXPECT_EQ(NumberRange::positive("Pa").describe(), "> 0 (Pa)");
  EXPECT_EQ(NumberRange::non_negative("1").describe(), ">= 0");
}

}  // namespace test_deck_reader
