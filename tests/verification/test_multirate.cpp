// Verification of MPM's multi-rate stepping (mpm.multirate, mpm/mpm_multirate.cpp): on
// a graded bar whose coarse cells allow four times the fine cells' step, two pulses run out of
// the fine band into the coarse cells, where their points step at four times the fine step.
//  - the points do step at several rates (the update count falls), and the scheme conserves
//    momentum node by node, so the bar's momentum stays what it was to round-off;
//  - the energy balance closes as well as with one step for all;
//  - the pulses arrive where d'Alembert's solution puts them, as accurately as with one step.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "verification/verification_support.hpp"

namespace test_multirate {

using namespace ballista;
using namespace ballista::verification;

namespace {

std::string fmt_number(double x) { return fmt::format("{:.17g}", x); }

constexpr double kHalfWidth = 0.2;  // m, the bump's half-width
constexpr double kV0 = 1.0e-3;      // m/s, its peak
constexpr double kEnd = 1.25;       // s: both pulses centred at |x| = 1.25, in the coarse cells

/// The bump v0 cos^2(pi x / 2w) for |x| < w.
double bump(double x) {
  if (std::abs(x) >= kHalfWidth) return 0.0;
  const double c = std::cos(std::acos(-1.0) * x / (2 * kHalfWidth));
  return kV0 * c * c;
}

// A bar along x (uniaxial strain: plane strain, nu = 0, symmetry faces top and bottom), E = rho =
// 1 so c = 1 m/s, with the bump's velocity at its centre (layers of 1/80 m, each its own body: one
// velocity field). Cells of 1/80 for |x| < 0.5, graded (ratio <= 1.2) to 1/20 outside, so a point
// in the coarse cells may step four times as long as one in the fine band. USAVG, pure FLIP.
std::string bar_deck(int ratio) {
  const double layer = 1.0 / 80.0;
  std::string d = "simulation: {solver: mpm, dimension: plane_strain, end_time: " + fmt_number(kEnd) +
                  ", cfl: 0.3}\n"
                  "mpm: {shape_function: gimp, update: usavg, flip: 1.0, multirate: " +
                  (ratio > 1 ? std::to_string(ratio) : std::string("none")) +
                  "}\n"
                  "materials:\n  m: {model: linear_elastic, density: 1, youngs_modulus: 1, poisson_ratio: 0}\n"
                  "grid: {lower: [-2.0, 0.0], upper: [2.0, 0.05], cell_size: 0.05, boundary: {y_min: symmetry, "
                  "y_max: symmetry}, refine: [{axis: x, from: -0.5, to: 0.5, cell_size: 0.0125}], grading: 1.2}\n"
                  "bodies:\n";
  auto body = [&](const std::string& name, double lo, double hi, double v) {
    d += "  - {name: " + name + ", material: m, velocity: [" + fmt_number(v) + ", 0], shape: {type: box, lower: [" +
         fmt_number(lo) + ", 0.0], upper: [" + fmt_number(hi) + ", 0.05]}}\n";
  };
  body("left", -2.0, -kHalfWidth, 0.0);
  const int layers = static_cast<int>(std::lround(2 * kHalfWidth / layer));
  for (int k = 0; k < layers; ++k) {
    const double lo = -kHalfWidth + k * layer;
    body("layer" + std::to_string(k), lo, lo + layer, bump(lo + 0.5 * layer));
  }
  body("right", kHalfWidth, 2.0, 0.0);
  return d;
}

struct BarRun {
  double momentum0 = 0.0, momentum = 0.0;  ///< kg m/s (per metre of thickness)
  double energy0 = 0.0, residual = 0.0;    ///< J: initial total, and the audit's residual at the end
  double error = 0.0;                      ///< mass-weighted RMS of v - v_exact over the bar, / v0
  double update_ratio = 1.0;               ///< point updates of one step for all over those made
  double substeps = 0.0, steps = 0.0;
};

BarRun run_bar(int ratio) {
  const Scenario sc = parse_deck(bar_deck(ratio), "multirate_bar.yaml");
  auto solver = make_solver(sc);
  BarRun r;
  auto momentum = [&] { return total_momentum(solver->points()); };
  r.momentum0 = momentum();
  r.energy0 = solver->energies().total();
  advance(*solver, sc.simulation.end_time);
  r.momentum = momentum();
  r.residual = solver->energies().total() - r.energy0;
  const FieldStore& pts = solver->points();
  const auto* x0 = pts.view<Vec3>("x0");
  const auto* v = pts.view<Vec3>("v");
  const auto* m = pts.real("mass");
  const double t = solver->time();
  double e2 = 0.0, mass = 0.0;
  for (Index i = 0; i < pts.size(); ++i) {
    // d'Alembert: half the bump runs each way (the displacement, ~1e-4 m, is left out of x).
    const double exact = 0.5 * (bump(x0[i][0] - t) + bump(x0[i][0] + t));
    e2 += m[i] * (v[i][0] - exact) * (v[i][0] - exact);
    mass += m[i];
  }
  r.error = std::sqrt(e2 / mass) / kV0;
  for (const auto& [key, value] : solver->result_values()) {
    if (key == "multirate_update_ratio") r.update_ratio = value;
    if (key == "multirate_substeps") r.substeps = value;
    if (key == "multirate_steps") r.steps = value;
  }
  return r;
}

}  // namespace

TEST(MultirateStep, PulsesIntoCoarseCellsMatchOneStepForAll) {
  const BarRun one = run_bar(1), multi = run_bar(4);
  std::printf("one step: error %.4e, residual %.3e J of %.3e; multi-rate: error %.4e, residual %.3e J, "
              "%.0f steps with %.0f substeps, update ratio %.3f, momentum %.17g -> %.17g\n",
              one.error, one.residual, one.energy0, multi.error, multi.residual, multi.steps, multi.substeps,
              multi.update_ratio, multi.momentum0, multi.momentum);
  report("multirate_bar_error", multi.error);
  report("multirate_bar_update_ratio", multi.update_ratio);
  // The run did step at two rates: the band, its grading and the cells within two of them step
  // fast, the rest slow. The band's 80 columns of cells and the gradings' 16 hold about two thirds
  // of the points, so one step for all would make about a fifth more updates (measured 1.24).
  EXPECT_GT(multi.steps, 0.0);
  EXPECT_GT(multi.update_ratio, 1.15);
  EXPECT_EQ(one.steps, 0.0);  // ratio 1 never takes substeps
  // Momentum node by node: the bar's total moves by round-off only (a few ulps per step).
  EXPECT_NEAR(multi.momentum, multi.momentum0, 1e-12 * std::abs(multi.momentum0));
  // The energy balance closes to the order of USAVG's own residual with one step (measured
  // 1.6e-4 of the pulse's energy with one step, 3.1e-4 multi-rate; a slow share that left out
  // the node's path would show the held forces' work unbooked).
  EXPECT_LT(std::abs(one.residual), 1e-3 * one.energy0);
  EXPECT_LT(std::abs(multi.residual), 1e-3 * multi.energy0);
  // The pulses: within 10 % of the single-rate error against d'Alembert (the slow points' step
  // is the coarse cells' own Courant step, as a uniform coarse grid would take).
  EXPECT_LT(multi.error, 1.1 * one.error);
}

TEST(MultirateStep, FastPointsLeavingWithinAStepLeaveTheSlowOnesAsTheyWere) {
  // A pellet (c = 1 m/s, moving out at 0.5 m/s in cells of 1/80) leaves the grid across its
  // x_max face, most of its points between two of the slow points' steps; an unstressed block
  // gliding at 0.01 m/s in cells of 1/20 far from it steps slow (own step 6 times the pellet's).
  // The deleted points take their mass away as booked; the slow points, whose index range moves
  // down each time, glide on exactly (a uniform motion is reproduced to round-off; a point that
  // missed its slow update, took another's weights, or was stepped twice would not).
  const std::string deck =
      "simulation: {solver: mpm, dimension: plane_strain, end_time: 0.4, cfl: 0.3, on_particle_exit: delete}\n"
      "mpm: {shape_function: gimp, update: usavg, flip: 1.0, multirate: 8}\n"
      "materials:\n  m: {model: linear_elastic, density: 1, youngs_modulus: 1, poisson_ratio: 0}\n"
      "grid: {lower: [0.0, 0.0], upper: [1.0, 0.1], cell_size: 0.05, boundary: {y_min: symmetry, y_max: symmetry}, "
      "refine: [{axis: x, from: 0.75, to: 1.0, cell_size: 0.0125}], grading: 1.2}\n"
      "bodies:\n"
      "  - {name: block, material: m, velocity: [0.01, 0], shape: {type: box, lower: [0.0, 0.0], upper: [0.4, 0.1]}}\n"
      "  - {name: pellet, material: m, velocity: [0.5, 0], shape: {type: box, lower: [0.85, 0.0], upper: [0.95, 0.1]}}\n";
  const Scenario sc = parse_deck(deck, "multirate_exit.yaml");
  auto solver = make_solver(sc);
  const double mass0 = solver->energies().mass;
  const Index n0 = solver->points().size();
  advance(*solver, sc.simulation.end_time);
  const EnergyTotals e = solver->energies();
  const FieldStore& pts = solver->points();
  const auto* x0 = pts.view<Vec3>("x0");
  const auto* x = pts.view<Vec3>("x");
  const auto* v = pts.view<Vec3>("v");
  Index block = 0;
  double moved = 0.0;  // the largest departure from the glide, m or m/s
  const Vec3 glide{{0.01, 0.0, 0.0}};
  const double t = solver->time();
  for (Index i = 0; i < pts.size(); ++i) {
    if (x0[i][0] > 0.5) continue;
    ++block;
    moved = std::max({moved, norm(x[i] - x0[i] - t * glide), norm(v[i] - glide)});
  }
  double steps = 0.0;
  for (const auto& [key, value] : solver->result_values())
    if (key == "multirate_steps") steps = value;
  std::printf("points %ld -> %ld, block %ld, largest departure from the glide %.3g, multi-rate steps %.0f\n",
              static_cast<long>(n0), static_cast<long>(pts.size()), static_cast<long>(block), moved, steps);
  EXPECT_GT(steps, 0.0);
  EXPECT_LT(pts.size(), n0);                    // the pellet left
  EXPECT_LT(moved, 1e-13);  // the slow block glides on (measured 3.6e-16: round-off on 0.4 m)
  EXPECT_NEAR(e.mass + e.removed_mass, mass0, 1e-12 * mass0);  // what left is booked
}

TEST(MultirateStep, WithPatchesASlowPointIsDampedAsWithOneStepForAll) {
  // The bar of the pulses with nested patches (1/40 over |x| < 0.75, 1/80 over |x| < 0.5) on 1/20
  // cells, and a PIC share of 10 %: one step for all damps a point in coarser cells than the step's
  // by (1 - flip) l_step / l_p per step, the rate its own cells' step would give. A slow point of
  // the multi-rate step must be damped as much per unit time: the PIC share's work over the run
  // (the audit's transfer term) is then one step's. R plain steps' share, 1 - flip^R, unscaled,
  // would damp the slow points in 1/20 cells at the fine step's rate, four times their own.
  auto patched = [](int ratio) {
    std::string d = bar_deck(ratio);
    const std::string band = ", refine: [{axis: x, from: -0.5, to: 0.5, cell_size: 0.0125}], grading: 1.2";
    d.replace(d.find(band), band.size(),
              ", patches: [{lower: [-0.75, 0.0], upper: [0.75, 0.05], cell_size: 0.025}, {lower: [-0.5, 0.0], "
              "upper: [0.5, 0.05], cell_size: 0.0125}]");
    d.replace(d.find("flip: 1.0"), 9, "flip: 0.9");
    const Scenario sc = parse_deck(d, "multirate_patched_bar.yaml");
    auto solver = make_solver(sc);
    const double e0 = solver->energies().total();
    advance(*solver, sc.simulation.end_time);
    double steps = 0.0;
    for (const auto& [key, value] : solver->result_values())
      if (key == "multirate_steps") steps = value;
    return std::array<double, 3>{solver->energies().transfer, e0, steps};
  };
  const auto one = patched(1), multi = patched(4);
  std::printf("PIC share's work: one step %.4e J, multi-rate %.4e J (%.0f steps), of %.4e J\n", one[0], multi[0],
              multi[2], one[1]);
  EXPECT_GT(multi[2], 0.0);
  EXPECT_LT(one[0], -1e-3 * one[1]);  // the share does damp: the comparison is not of two zeros
  // Within 10 % of one step's: measured -6.42e-10 J against -6.36e-10 J (1 %); with the slow
  // points' share taken as R plain steps', -1.07e-9 J (68 % more).
  EXPECT_NEAR(multi[0], one[0], 0.1 * std::abs(one[0]));
}

TEST(MultirateStep, ABodyAtRestOutOfReachDoesNotHoldTheStep) {
  // A pellet (c = 1 m/s, 0.5 m/s) in cells of 1/20 flies at a plate at rest in cells of 1/80, 11
  // empty coarse cells away. The plate's own step is 0.3 / 80 = 3.75e-3 s, the pellet's
  // 0.3 / 20 / 1.5 = 1e-2 s. Until the pellet comes within reach, no change can arrive at the
  // plate within a step (multirate_idle.cpp), so the step is the pellet's; at the impact the
  // plate holds it to its own again, and the run is the one-step-for-all run within the
  // multi-rate scheme's own error.
  auto deck = [](const char* multirate) {
    return std::string("simulation: {solver: mpm, dimension: plane_strain, end_time: 1.6, cfl: 0.3}\n"
                       "mpm: {shape_function: gimp, update: usavg, flip: 1.0, multirate: ") +
           multirate +
           "}\n"
           "materials:\n  m: {model: linear_elastic, density: 1, youngs_modulus: 1, poisson_ratio: 0}\n"
           "grid: {lower: [0.0, 0.0], upper: [1.2, 0.05], cell_size: 0.05, boundary: {y_min: symmetry, y_max: "
           "symmetry}, refine: [{axis: x, from: 0.7, to: 0.9, cell_size: 0.0125}], grading: 1.2}\n"
           "bodies:\n"
           "  - {name: pellet, material: m, velocity: [0.5, 0], shape: {type: box, lower: [0.1, 0.0], upper: [0.2, 0.05]}}\n"
           "  - {name: plate, material: m, shape: {type: box, lower: [0.75, 0.0], upper: [0.85, 0.05]}}\n";
  };
  struct Run {
    double dt0 = 0.0, rest_departure = 0.0, momentum0 = 0.0, momentum = 0.0, plate_momentum = 0.0;
    double residual = 0.0, energy0 = 0.0;
    long steps_before = 0, steps = 0;
  };
  auto run = [&](const char* multirate) {
    const Scenario sc = parse_deck(deck(multirate), "multirate_idle.yaml");
    auto solver = make_solver(sc);
    Run r;
    auto sums = [&](bool plate_only) {
      const FieldStore& pts = solver->points();
      const auto* v = pts.view<Vec3>("v");
      const auto* m = pts.real("mass");
      const auto* x0 = pts.view<Vec3>("x0");
      double p = 0.0;
      for (Index i = 0; i < pts.size(); ++i)
        if (!plate_only || x0[i][0] > 0.5) p += m[i] * v[i][0];
      return p;
    };
    r.dt0 = solver->stable_dt();
    r.momentum0 = sums(false);
    r.energy0 = solver->energies().total();
    // 0.9 s: the pellet's face at 0.65, 0.1 m (5 coarse cells) short of the plate.
    advance(*solver, 0.9);
    // The steps the fastest points took: the substeps of the steps that took some, and the others.
    r.steps_before = solver->steps();
    for (const auto& [key, value] : solver->result_values()) {
      if (key == "multirate_substeps") r.steps_before += static_cast<long>(value);
      if (key == "multirate_steps") r.steps_before -= static_cast<long>(value);
    }
    {
      const FieldStore& pts = solver->points();
      const auto* x0 = pts.view<Vec3>("x0");
      const auto* x = pts.view<Vec3>("x");
      const auto* v = pts.view<Vec3>("v");
      for (Index i = 0; i < pts.size(); ++i)
        if (x0[i][0] > 0.5) r.rest_departure = std::max({r.rest_departure, norm(x[i] - x0[i]), norm(v[i])});
    }
    advance(*solver, sc.simulation.end_time);
    r.steps = solver->steps();
    r.momentum = sums(false);
    r.plate_momentum = sums(true);
    r.residual = solver->energies().total() - r.energy0;
    return r;
  };
  const Run one = run("none"), multi = run("8");
  std::printf("first step: one %.4g s, multi-rate %.4g s; (sub)steps to 0.9 s: %ld and %ld, to the end: %ld and %ld; "
              "plate momentum %.6e and %.6e of %.6e; residual %.3e and %.3e J of %.3e\n",
              one.dt0, multi.dt0, one.steps_before, multi.steps_before, one.steps, multi.steps, one.plate_momentum,
              multi.plate_momentum, one.momentum0, one.residual, multi.residual, one.energy0);
  // The plate's own step holds one step for all (240 steps to 0.9 s); the pellet's holds the
  // multi-rate substeps (its cell there is 0.046 m: 0.3 x 0.046 / 1.5 = 9.2e-3 s, 98 substeps),
  // eight to a step, which the idle plate takes at once.
  EXPECT_NEAR(one.dt0, 3.75e-3, 1e-9);
  EXPECT_LT(multi.steps_before, one.steps_before / 2);
  EXPECT_GT(multi.dt0, 8 * one.dt0);
  // The plate was left exactly at rest (its idle updates are no-ops, bit for bit).
  EXPECT_EQ(multi.rest_departure, 0.0);
  // The impact happened (the plate took a good part of the momentum), momentum is conserved to
  // round-off, and the plate's share is the one-step-for-all run's within 1 % (the multi-rate
  // scheme's error on the pulses above is of that order: their 10 % bound is on a 6 % error).
  EXPECT_GT(one.plate_momentum, 0.2 * one.momentum0);
  EXPECT_NEAR(multi.momentum, multi.momentum0, 1e-12 * std::abs(multi.momentum0));
  EXPECT_NEAR(multi.plate_momentum, one.plate_momentum, 0.01 * one.plate_momentum);
  // And the energy balance closes as one step's does (the impact's residual, 0.8 % of the energy
  // with one step for all: within a tenth of it).
  EXPECT_NEAR(multi.residual, one.residual, 0.1 * std::abs(one.residual));
}

TEST(MultirateStep, IdlePointsWaitForWhatCanReachThem) {
  // What can reach a point at rest within a step, each in a deck where it would otherwise reach an
  // idle point (the step's own check, check_idle_points_rest, then stops the run): a pellet fast
  // against its wave speed (20 m/s, c = 1 m/s) crossing seven empty cells at 16 substeps of CFL
  // 0.5; a pellet activated three cells from a plate; an explosive lit by the program burn while a
  // flyer far from it moves.
  const std::string bar = "materials:\n  m: {model: linear_elastic, density: 1, youngs_modulus: 1, poisson_ratio: 0}\n"
                          "grid: {lower: [0.0, 0.0], upper: [2.4, 0.05], cell_size: 0.05, boundary: {y_min: symmetry, "
                          "y_max: symmetry}}\n";
  const std::string crossing =
      "simulation: {solver: mpm, dimension: plane_strain, end_time: 0.05, cfl: 0.5}\n"
      "mpm: {shape_function: gimp, update: usavg, flip: 1.0, multirate: 16}\n" + bar +
      "bodies:\n"
      "  - {name: pellet, material: m, velocity: [20, 0], shape: {type: box, lower: [0.1, 0.0], upper: [0.2, 0.05]}}\n"
      "  - {name: plate, material: m, shape: {type: box, lower: [0.55, 0.0], upper: [0.65, 0.05]}}\n";
  const std::string activated =
      "simulation: {solver: mpm, dimension: plane_strain, end_time: 0.2, cfl: 0.3}\n"
      "mpm: {shape_function: gimp, update: usavg, flip: 1.0, multirate: 8}\n" + bar +
      "bodies:\n"
      "  - {name: far, material: m, velocity: [-0.1, 0], shape: {type: box, lower: [2.0, 0.0], upper: [2.1, 0.05]}}\n"
      "  - {name: pellet, material: m, velocity: [5, 0], activation_time: 0.05, shape: {type: box, lower: [0.4, 0.0], "
      "upper: [0.5, 0.05]}}\n"
      "  - {name: plate, material: m, shape: {type: box, lower: [0.65, 0.0], upper: [0.75, 0.05]}}\n";
  const std::string lit =
      "simulation: {solver: mpm, dimension: plane_strain, end_time: 10.0e-6, cfl: 0.3, on_particle_exit: delete}\n"
      "materials:\n  tnt: {preset: tnt}\n"
      "  steel: {model: linear_elastic, density: 7850, bulk_modulus: 160.0e9, shear_modulus: 79.0e9}\n"
      "mpm: {shape_function: gimp, update: usavg, multirate: 8, flip: 1.0}\n"
      "grid: {lower: [-0.06, 0.0], upper: [0.08, 1.0e-3], cell_size: 1.0e-3, boundary: {y_min: symmetry, y_max: symmetry}}\n"
      "bodies:\n"
      "  - {name: charge, material: tnt, particles_per_cell: 2, shape: {type: box, lower: [0.0, 0.0], upper: [10.0e-3, 1.0e-3]}}\n"
      "  - {name: plate, material: steel, particles_per_cell: 2, shape: {type: box, lower: [10.0e-3, 0.0], upper: [12.076e-3, "
      "1.0e-3]}}\n"
      "  - {name: flyer, material: steel, particles_per_cell: 2, velocity: [-1.0, 0], shape: {type: box, lower: [60.0e-3, "
      "0.0], upper: [62.0e-3, 1.0e-3]}}\n"
      "detonation:\n  points:\n    - {position: [0.0, 0.5e-3], time: 0.0}\n";
  for (const auto& [name, deck] : {std::pair{"crossing", crossing}, std::pair{"activated", activated}, std::pair{"lit", lit}}) {
    SCOPED_TRACE(name);
    const Scenario sc = parse_deck(deck, std::string(name) + ".yaml");
    auto solver = make_solver(sc);
    // The run loop's step, landing on activations as `ballista run` does.
    EXPECT_NO_THROW({
      while (solver->time() < sc.simulation.end_time * (1.0 - 1e-12))
        solver->step(std::min(solver->land_step(solver->stable_dt()), sc.simulation.end_time - solver->time()));
    });
    EXPECT_GT(solver->steps(), 0);
  }
}

TEST(MultirateStep, WhatItDoesNotDoYetIsADeckError) {
  // USL and MUSL, the F-bar and XPIC are refused with the key named (the scheme is USAVG's).
  const std::string usavg = "update: usavg";
  for (const std::string other : {"update: usl", "update: musl", "update: usavg, anti_locking: fbar",
                                   "update: usavg, flip: 0.99, xpic_order: 2"}) {
    std::string deck = bar_deck(4);
    deck.replace(deck.find(usavg), usavg.size(), other);
    if (other.find("flip:") != std::string::npos) deck.replace(deck.find(", flip: 1.0"), 11, "");  // one flip key
    try {
      make_solver(parse_deck(deck, "multirate_bar.yaml"));
      ADD_FAILURE() << other << " was accepted";
    } catch (const DeckError& e) {
      EXPECT_EQ(e.key_path(), "mpm.multirate") << other;
      EXPECT_NE(std::string(e.what()).find("multi-rate stepping"), std::string::npos) << e.what();
    }
  }
}

}  // namespace test_multirate
