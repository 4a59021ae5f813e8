// Verification of MPM on a graded grid (grid.refine, geometry/grid_axes.hpp,
// mpm/graded_shape_functions.hpp):
//  - B1 (axis-aligned MMS) and B2 (generalized vortex MMS) keep their observed orders when part
//    of the domain is refined, the rest graded to cells twice as large: the graded interpolation
//    and the per-cell seeding add no lower-order error;
//  - a stress pulse crossing from fine to coarse cells leaves less than 1 % of its energy behind
//    (a reflection at the change of cell size), beyond what the uniform fine grid leaves.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "verification/verification_support.hpp"

namespace test_graded_grid {

using namespace ballista;
using namespace ballista::verification;

namespace {

std::string fmt_number(double x) { return fmt::format("{:.17g}", x); }

std::string zone(const char* axis, double from, double to, double h) {
  return "{axis: " + std::string(axis) + ", from: " + fmt_number(from) + ", to: " + fmt_number(to) +
         ", cell_size: " + fmt_number(h) + "}";
}

/// The B1 cube's bands at H/2 (0.25 < x < 0.5, 0.5 < y < 0.75), graded with ratio <= 1.5.
std::vector<std::string> graded_b1_sets(double h) {
  return {"grid.refine=[" + zone("x", 0.25, 0.5, h / 2) + ", " + zone("y", 0.5, 0.75, h / 2) + "]", "grid.grading=1.5"};
}

}  // namespace

TEST(GradedGrid, B1KeepsItsOrderWithARefinedBand) {
  // Cells H = 1/4 and 1/8, and H/2 in the bands 0.25 < x < 0.5 and 0.5 < y < 0.75, graded with
  // ratio <= 1.5 (GIMP, USL, pure FLIP as the uniform B1 test; ~10 s). Measured: 2.08e-2 and
  // 5.75e-3 (order 1.85; uniform 3.28e-2 and 9.89e-3). The uniform test's bound on the order,
  // 1.5, holds here; slow_graded_grid.cpp adds H = 1/16 and explains its 1.47.
  const std::vector<double> H = {0.25, 0.125};
  std::vector<MmsError> graded, uniform;
  for (double h : H) {
    graded.push_back(run_mms(h, graded_b1_sets(h)));
    uniform.push_back(run_mms(h));
    std::printf("B1 H = %g: graded L2 %.4e (%ld particles), uniform L2 %.4e (%ld)\n", h, graded.back().l2,
                graded.back().particles, uniform.back().l2, uniform.back().particles);
  }
  const double order = observed_order(graded[0].l2, graded[1].l2);
  report("graded_b1_order", order);
  EXPECT_GE(order, 1.5);
  // Refining part of the domain does not make the answer worse than the uniform coarse grid's.
  for (std::size_t k = 0; k < H.size(); ++k) EXPECT_LT(graded[k].l2, 1.1 * uniform[k].l2) << H[k];
}

TEST(GradedGrid, B2KeepsItsOrderWithARefinedBand) {
  // The vortex annulus (radius 0.75 to 1.25) at H = 1/16 and 1/32 with the band -0.5 < x < 0.5
  // at H/2 (it crosses the annulus twice), ratio <= 1.5. The uniform test asserts 1.7 (measured
  // 1.96 with GIMP, 1.97 linear); the same bound here.
  for (const char* sf : {"gimp", "linear"}) {
    std::vector<MmsError> e;
    for (double h : {0.0625, 0.03125}) {
      e.push_back(run_vortex(h, sf, {"grid.refine=[" + zone("x", -0.5, 0.5, h / 2) + "]", "grid.grading=1.5"}));
      std::printf("B2 %s H = %g: graded L2 %.4e (%ld particles)\n", sf, h, e.back().l2, e.back().particles);
    }
    const double order = observed_order(e[0].l2, e[1].l2);
    report(std::string("graded_b2_order_") + sf, order);
    EXPECT_GE(order, 1.7) << sf;
  }
}

namespace {

// A bar along x (uniaxial strain: plane strain, nu = 0, symmetry faces top and bottom), E = rho =
// 1 so c = 1 m/s, at rest and unstressed, with a smooth velocity bump v = v0 cos^2(pi x / 2w)
// for |x| < w at its centre (layers of 1/80 m, each its own body: one velocity field). The bump
// splits into two pulses running out at c. Graded: cells of 1/80 for |x| < 0.5, graded (ratio
// <= 1.2) to 1/20 outside. At t = 1.25 both pulses are past the gradings (they end by |x| = 0.8).
std::string bar_deck(bool graded) {
  const double w = 0.2, layer = 1.0 / 80.0, v0 = 1.0e-3;
  std::string d =
      "simulation: {solver: mpm, dimension: plane_strain, end_time: 1.25, cfl: 0.3}\n"
      "mpm: {shape_function: gimp, update: usl, flip: 1.0}\n"
      "materials:\n  m: {model: linear_elastic, density: 1, youngs_modulus: 1, poisson_ratio: 0}\n"
      "grid: {lower: [-2.0, 0.0], upper: [2.0, 0.05], cell_size: " +
      std::string(graded ? "0.05" : "0.0125") + ", boundary: {y_min: symmetry, y_max: symmetry}" +
      (graded ? ", refine: [{axis: x, from: -0.5, to: 0.5, cell_size: 0.0125}], grading: 1.2" : "") + "}\nbodies:\n";
  auto body = [&](const std::string& name, double lo, double hi, double v) {
    d += "  - {name: " + name + ", material: m, velocity: [" + fmt_number(v) + ", 0], shape: {type: box, lower: [" +
         fmt_number(lo) + ", 0.0], upper: [" + fmt_number(hi) + ", 0.05]}}\n";
  };
  body("left", -2.0, -w, 0.0);
  const int layers = static_cast<int>(std::lround(2 * w / layer));
  for (int k = 0; k < layers; ++k) {
    const double lo = -w + k * layer, mid = lo + 0.5 * layer;
    const double c = std::cos(std::acos(-1.0) * mid / (2 * w));
    body("layer" + std::to_string(k), lo, lo + layer, v0 * c * c);
  }
  body("right", w, 2.0, 0.0);
  return d;
}

/// Kinetic + internal energy of the points that started within |x| < 0.45 (the fine band), over
/// the total, at the end.
double energy_left_behind(bool graded) {
  const Scenario sc = parse_deck(bar_deck(graded), graded ? "graded_bar.yaml" : "uniform_bar.yaml");
  auto solver = make_solver(sc);
  const double total = solver->energies().total();
  advance(*solver, sc.simulation.end_time);
  const FieldStore& pts = solver->points();
  const auto* x0 = pts.view<Vec3>("x0");
  const auto* v = pts.view<Vec3>("v");
  const auto* m = pts.real("mass");
  const auto* e = pts.real("internal_energy");
  double inside = 0.0;
  for (Index p = 0; p < pts.size(); ++p)
    if (std::abs(x0[p][0]) < 0.45) inside += 0.5 * m[p] * dot(v[p], v[p]) + e[p];
  return inside / total;
}

}  // namespace

TEST(GradedGrid, APulseCrossingACoarseningLeavesLessThanOnePercentBehind) {
  const double graded = energy_left_behind(true), uniform = energy_left_behind(false);
  std::printf("pulse energy left in the fine band: graded %.3e, uniform %.3e of the total\n", graded, uniform);
  report("graded_reflection", graded - uniform);
  // The uniform fine grid's own remainder is the dispersive tail (a few 1e-3); the grading's
  // reflection is what the graded grid leaves beyond it.
  EXPECT_LT(graded - uniform, 0.01);
  EXPECT_LT(uniform, 0.01);  // not vacuous: the pulses did leave the band
}

}  // namespace test_graded_grid
