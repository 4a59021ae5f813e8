// A body read from a surface file or a volume mesh runs as its analytic twin: the Taylor bar of
// examples/taylor_bar_mpm_3d.yaml, as a cylinder, as examples/taylor_bar_mpm_3d_surface.yaml's STL
// (the same bar, 128 facets around, in mm) and as examples/taylor_bar_mpm_3d_mesh.yaml's Exodus
// mesh (128 sectors, tetrahedra and hexahedra, in mm), seeds the same particles and deforms alike.
#include <gtest/gtest.h>

#include <string>

#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_surface_body {

using namespace ballista;

namespace {

RunResult run_deck(const std::string& name, const std::filesystem::path& out) {
  // 1 mm cells (2,015 particles) to 30 us: the bar's impact and the start of the mushroom, ~1 s.
  const Scenario sc = read_deck(std::string(BALLISTA_SOURCE_DIR) + "/examples/" + name,
                                {"grid.cell_size=1.0e-3", "simulation.end_time=30.0e-6"});
  RunOptions o;
  o.out_dir = out.string();
  o.threads = 1;
  o.progress = false;
  o.plots = false;
  return run_simulation(sc, o);
}

double probe(const RunResult& r, const std::string& name) {
  for (const auto& [n, v] : r.probes)
    if (n == name) return v;
  return NAN;
}

/// Runs `deck` beside the analytic cylinder and expects the same steps and probes. The inscribed
/// 128-gon of the STL and of the mesh has 0.9996 of the circle's area: on this lattice no particle
/// lies in the sliver between them, so both runs seed the same points. The tolerance (1e-3 of the
/// length, about one particle's share of it) leaves room for a particle of the sliver on another
/// lattice.
void expect_runs_as_the_cylinder(const std::string& deck) {
  test::TempDir dir;
  const RunResult cylinder = run_deck("taylor_bar_mpm_3d.yaml", dir.path / "cylinder");
  const RunResult read = run_deck(deck, dir.path / "read");
  ASSERT_TRUE(cylinder.ok) << cylinder.error;
  ASSERT_TRUE(read.ok) << read.error;
  EXPECT_EQ(read.steps, cylinder.steps);
  for (const char* p : {"final_length", "foot_radius", "max_eqps"})
    EXPECT_NEAR(probe(read, p), probe(cylinder, p), 1e-3 * std::abs(probe(cylinder, p))) << p;
}

}  // namespace

TEST(SurfaceBody, TheStlTaylorBarRunsAsTheAnalyticCylinder) {
  expect_runs_as_the_cylinder("taylor_bar_mpm_3d_surface.yaml");
}

TEST(SurfaceBody, TheExodusTaylorBarRunsAsTheAnalyticCylinder) {
  expect_runs_as_the_cylinder("taylor_bar_mpm_3d_mesh.yaml");
}

}  // namespace test_surface_body
