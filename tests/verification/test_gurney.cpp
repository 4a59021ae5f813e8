// Detonation products driving metal (issue 15 item 5): Gurney's open-faced sandwich and cylinder.
// The open-faced sandwich of Gurney
// (R.W. Gurney, BRL Report 405, 1943; P.W. Cooper, Explosives Engineering, 1996, ch. 27) in MPM,
// plane strain, made one-dimensional by symmetry faces: a 10 mm layer of TNT (the `tnt` preset,
// JWL products) lit on its free face, a steel plate on the other face. The plate's terminal
// velocity against V = sqrt(2E) [((1 + 2 M/C)^3 + 1) / (6 (1 + M/C)) + M/C]^{-1/2} with TNT's
// Gurney constant sqrt(2E) = 2440 m/s (Cooper's table; data/materials.yaml tnt notes), at
// M/C = 0.5 and 1. Bound 10 % (the issue's): Gurney's formula is itself an energy-balance model
// with a linear gas velocity profile, fitted to experiments to about that accuracy, and the run
// stops when the gas has expanded ~10 charge thicknesses (what the products still hold then is
// a few % of the plate's energy). Also checked: the energy balance (kinetic + stress-power
// internal energy; the products' chemical energy enters as their E) closes to 2 % of the chemical
// energy released (measured 1.0 % at these 0.5 mm cells and CFL 0.3; the residual is MPM's
// time-integration error — it falls with the CFL, 3.6 % -> 1.5 % at 0.25 mm from CFL 0.3 to 0.1 —
// not the burn's: an instantaneous burn changes it by 0.1 %), and the lighting times follow the
// distance from the detonator over D exactly. 20 cells across the charge, 2 x 2 points per cell.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "materials/explosive_eos.hpp"
#include "run/simulation.hpp"
#include "verification/gurney_cylinder_support.hpp"
#include "verification/gurney_sandwich_support.hpp"
#include "verification/verification_support.hpp"

namespace ballista::test_gurney {
namespace {

using gurney_sandwich::deck;
using gurney_sandwich::drive;
using gurney_sandwich::mean_x_velocity;
using gurney_sandwich::PlateResult;

TEST(GurneySandwich, PlateReachesTheGurneyVelocity) {
  for (double mc : {0.5, 1.0}) {
    const PlateResult r = drive(mc);
    const double gurney = gurney_open_sandwich(2440.0, mc);
    std::printf("open-faced sandwich, M/C = %.2f: plate %.0f m/s, Gurney %.0f m/s (%.1f %%), energy residual %.4f, "
                "lighting-time error %.3g m\n",
                mc, r.velocity, gurney, 100.0 * (r.velocity / gurney - 1.0), r.residual, r.lighting_error);
    EXPECT_NEAR(r.velocity / gurney, 1.0, 0.10) << mc;
    EXPECT_LT(r.residual, 0.02) << mc;
    EXPECT_LT(r.lighting_error, 1e-9);  // straight lines from the detonator: exact
  }
}

// The same sandwich with the OTM solver (the shared material library and program burn): the two
// bodies share one node set (otm.nodes: shared; with a node set each they would not interact)
// and adaptivity keeps the expanding products resolved (without it their LME solves fail at
// ~4 us, the gas stretched 12x). M/C = 1. The node re-generations make a coarse run sensitive to
// round-off: the detonation time shifted by 1e-13 s, five draws, gave +3.4 to +15.1 % at 1 mm
// (two builds), +3.4 to +8.1 % at 0.5 mm and +0.7 % at 0.25 mm (docs/validation.md). So here, at
// 1 mm within make test's time: the mean of three draws within 20 % (every draw measured so far is
// within 15.1 %; a plate the products did not drive, or drove twice, is far outside), and each
// run's worst energy residual below 7.5 % of the chemical energy (seven draws: 1.1 to 4.8 %; what
// the re-generations leave unbooked, the momentum form's re-lumping, is first order in h: 0.4 to
// 2.0 % at 0.5 mm). The issue's 10 % at 0.5 mm is slow_gurney_otm.cpp (label slow).
TEST(GurneySandwich, OtmPlateIsDrivenNearTheGurneyVelocity) {
  const double mean = gurney_sandwich::otm_mean_plate_velocity(1.0e-3, 0.075);
  EXPECT_NEAR(mean / gurney_open_sandwich(2440.0, 1.0), 1.0, 0.20);
}

// Decks that would run without the explosive doing what they say are refused: under OTM with a
// node set per body (the products would push nothing), and with preparation stages (the lighting
// times count from t = 0, so the charge would go off during the stage).
TEST(GurneySandwich, DecksWhereTheChargeWouldActOnNothingAreRefused) {
  std::string otm = deck(1.0e-3, true);
  otm.replace(otm.find("nodes: shared, "), 15, "");
  auto error_of = [](const std::string& yaml) -> std::string {
    try {
      make_solver(parse_deck(yaml, "refused.yaml"));
    } catch (const DeckError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error_of(otm).find("otm.nodes"), std::string::npos) << error_of(otm);
  const std::string staged = deck(1.0e-3) +
                             "stages:\n  - {name: settle, duration: 1.0e-6, damping: 1.0e5}\n";
  EXPECT_NE(error_of(staged).find("preparation stages"), std::string::npos) << error_of(staged);
}

// The Gurney cylinder (R.W. Gurney 1943; Cooper 1996 ch. 27): a long TNT cylinder (radius 10 mm)
// in a steel case, V = sqrt(2E) (M/C + 1/2)^{-1/2}. MPM, axisymmetric, an axial slice of 1 mm
// between symmetry faces (an infinitely long cylinder, as Gurney's formula assumes), lit on the
// axis; the case is strengthless (J2 with a 1 MPa yield stress: Gurney's energy balance has no
// case strength; the seed's 4340 case at 750 MPa is 3-5 % slower, docs/validation.md). Measured at
// 20 us, when the case has expanded ~4x in radius (the gas ~16x in volume; the standard cylinder
// test reads the wall velocity at 7 volumes). Bound 10 % (the issue's); measured -1.7 %..+1.0 %
// at these 0.5 mm cells (20 across the charge), within 5 % at 1 and 0.25 mm.
TEST(GurneyCylinder, CaseReachesTheGurneyVelocity) {
  for (double mc : {1.0, 2.0}) {
    const Scenario sc = parse_deck(gurney::mpm_cylinder_deck(mc, 0.5e-3), "gurney_cylinder.yaml");
    auto solver = make_solver(sc);
    const double worst = verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
    const EnergyTotals e = solver->energies();
    const double V = mean_x_velocity(solver->points(), 1), gurney = gurney_cylinder(2440.0, mc);
    std::printf("Gurney cylinder, M/C = %.1f: case %.0f m/s, Gurney %.0f m/s (%.1f %%), energy residual %.4f of the "
                "chemical energy\n",
                mc, V, gurney, 100.0 * (V / gurney - 1.0), worst / e.chemical);
    EXPECT_NEAR(V / gurney, 1.0, 0.10) << mc;
    EXPECT_LT(worst / e.chemical, 0.02) << mc;
  }
}

}  // namespace
}  // namespace ballista::test_gurney

namespace ballista::test_gurney {
namespace {

// An ideal-gas charge released from rest (issue 15 item 5: "expands with the energy of its
// isentrope"): a 10 mm slab of gamma = 3 products (rho0 1630, D 6930; volume burn at once,
// burn_cells 0) lit on one face expands freely into vacuum on both sides, MPM, plane strain made
// 1D. Each point lights at X = 1 with E = Q and then follows its isentrope E X^(gamma-1) = Q, so
// the work the gas has done, which is the kinetic energy, is sum_p Q (1 - X_p^(1-gamma)) V0_p
// with each point's own X = J at that time: an independent prediction of the kinetic energy
// from the points' volumes alone. Bound 3 %: measured -1.45 % (residual 0.5 %); what separates the two is
// the gas compressed behind the front before it expands (not quite isentropic from X = 1) and
// MPM's time-integration error (1 % in the sandwich).
TEST(IdealGasExpansion, KineticEnergyIsTheIsentropesWork) {
  const Scenario sc = parse_deck(R"(
simulation: {solver: mpm, dimension: plane_strain, end_time: 8.0e-6, cfl: 0.3, on_particle_exit: stop}
materials:
  gas: {model: explosive, density: 1630, detonation_speed: 6930, products: ideal_gas, gamma: 3}
mpm: {shape_function: gimp, update: musl, flip: 0.99}
grid: {lower: [-0.06, 0], upper: [0.07, 1.0e-3], cell_size: 0.5e-3, boundary: {y_min: symmetry, y_max: symmetry}}
bodies:
  - {name: charge, material: gas, shape: {type: box, lower: [0, 0], upper: [10.0e-3, 1.0e-3]}, particles_per_cell: 2}
detonation: {points: [{position: [0, 0.5e-3], time: 0}], burn_cells: 0}
)",
                                 "ideal_gas_expansion.yaml");
  auto solver = make_solver(sc);
  const EnergyTotals e0 = solver->energies();
  while (solver->time() < sc.simulation.end_time)
    solver->step(std::min(solver->stable_dt(), sc.simulation.end_time - solver->time() + 1e-15));
  const EnergyTotals e = solver->energies();
  const double Q = detonation_energy(ideal_gas_products(1630.0, 6930.0, 3.0));
  const FieldStore& pts = solver->points();
  const auto* F = pts.view<Mat3>("F");
  const auto* vol0 = pts.real("volume0");
  const auto* burnt = pts.real("burn_fraction");
  double isentrope_work = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    ASSERT_EQ(burnt[p], 1.0);  // the whole charge has burnt by 8 us (10 mm at 6.93 km/s: 1.4 us)
    isentrope_work += Q * (1.0 - std::pow(det(F[p]), -2.0)) * vol0[p];
  }
  std::printf("ideal-gas expansion: kinetic energy %.6g J/m, isentropes' work %.6g J/m (%.2f %%), chemical %.6g J/m, "
              "residual %.4f of it\n",
              e.kinetic, isentrope_work, 100.0 * (e.kinetic / isentrope_work - 1.0), e.chemical,
              (e.total() - e0.total()) / e.chemical);
  EXPECT_NEAR(e.kinetic / isentrope_work, 1.0, 0.03);
  EXPECT_LT(std::abs(e.total() - e0.total()) / e.chemical, 0.02);
}

}  // namespace
}  // namespace ballista::test_gurney
