// OTM honours a symmetry face (its nodes on the plane keep zero normal velocity): a half model
// with the plane gives the full model's half. An elastic block (plane strain, 40 x 20 mm, rubber)
// is dropped at 20 m/s on a rigid wall and bounces, expanding sideways; the full block is
// symmetric about x = 0 and the half block is cut there. Exact symmetry would make them agree to
// round-off if the shape functions were mirror images; they are not quite: the half model's
// local max-entropy supports end at the plane, where the full model's reach across it. So the
// bounds are the discretisation's, measured at 2.5 mm nodes: width within 0.01 %, height equal,
// kinetic energy within 0.3 % (bounds 0.2 % and 1 %).
#include <gtest/gtest.h>

#include <string>

#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace ballista::test_otm_symmetry {
namespace {

std::string deck(bool half) {
  return std::string("simulation: {solver: otm, dimension: plane_strain, end_time: 3.0e-4, cfl: 0.3}\n") +
         "materials:\n  rubber: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n" +
         "grid: {lower: [" + (half ? "0.0" : "-0.05") + ", 0.0], upper: [0.05, 0.06], cell_size: 0.0025, " +
         "boundary: {y_min: wall" + (half ? ", x_min: symmetry" : "") + "}}\n" +
         "bodies:\n  - {name: block, material: rubber, shape: {type: box, lower: [" + (half ? "0.0" : "-0.02") +
         ", 0.0], upper: [0.02, 0.02]}, velocity: [0, -20]}\n" +
         "probes:\n  - {name: width, type: extent, body: block, axis: x}\n"
         "  - {name: height, type: extent, body: block, axis: y}\n"
         "  - {name: kinetic, type: energy, field: kinetic}\n";
}

std::vector<std::pair<std::string, double>> run(bool half) {
  test::TempDir dir{half ? "otm_half" : "otm_full"};
  RunOptions o;
  o.out_dir = dir.path.string();
  o.progress = false;
  o.threads = 1;
  const RunResult r = run_simulation(parse_deck(deck(half), "otm_symmetry.yaml"), o);
  EXPECT_TRUE(r.ok) << r.error;
  return r.probes;
}

TEST(OtmSymmetry, AHalfModelGivesTheFullModelsHalf) {
  const auto full = run(false), half = run(true);
  ASSERT_EQ(full.size(), 3u);
  ASSERT_EQ(half.size(), 3u);
  EXPECT_NEAR(2.0 * half[0].second / full[0].second, 1.0, 0.002) << "width";
  EXPECT_NEAR(half[1].second / full[1].second, 1.0, 0.002) << "height";
  EXPECT_NEAR(2.0 * half[2].second / full[2].second, 1.0, 0.01) << "kinetic energy";
  // Not vacuous: the block has bounced and spread (Poisson expansion against the wall).
  EXPECT_GT(full[0].second, 0.0401);
}

}  // namespace
}  // namespace ballista::test_otm_symmetry
