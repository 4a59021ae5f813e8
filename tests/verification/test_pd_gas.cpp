// Detonation products as a peridynamic gas (issue 15 item 3; seed 001 "Gases as Peridynamic
// Materials", peridynamics/gas_pass.hpp): the density measure against its closed form, the ideal
// gas released from rest against the work of its isentropes, and the Gurney cylinder.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "deck/deck_reader.hpp"
#include "materials/explosive_eos.hpp"
#include "peridynamics/gas_pass.hpp"
#include "peridynamics/pd_solver.hpp"
#include "run/simulation.hpp"
#include "verification/gurney_cylinder_support.hpp"
#include "verification/verification_support.hpp"

namespace ballista::test_pd_gas {
namespace {

double result(const Solver& s, const std::string& key) {
  for (const auto& [k, v] : s.result_values())
    if (k == key) return v;
  ADD_FAILURE() << "no result " << key;
  return 0.0;
}

// X_i = [(1/V) sum_j (r/p) dV_j]^(-d) (m = 1): under a uniform dilatation p = lambda r of every
// bond, X = lambda^d exactly, for interior and surface points alike (the measure is normalised by
// the point's own family volume). And the pair forces are equal and opposite bond by bond, so
// with any pressures the total force is zero (to round-off of the sum).
TEST(PdGas, DensityMeasureOfAUniformDilatationAndForceBalance) {
  for (const char* dim : {"plane_strain", "3d"}) {
    const bool three = std::string(dim) == "3d";
    const std::string deck = std::string("simulation: {solver: peridynamics, dimension: ") + dim + R"(, end_time: 1.0e-6}
materials:
  tnt: {preset: tnt}
  steel: {model: linear_elastic, density: 7850, bulk_modulus: 160.0e9, shear_modulus: 79.0e9}
grid: {lower: [-0.01, -0.01, -0.01], upper: [0.01, 0.01, 0.01], cell_size: 1.0e-3}
bodies:
  - {name: charge, material: tnt, shape: {type: box, lower: [-4.0e-3, -4.0e-3, -3.0e-3], upper: [2.0e-3, 4.0e-3, 3.0e-3]}}
  - {name: plate, material: steel, shape: {type: box, lower: [2.0e-3, -4.0e-3, -3.0e-3], upper: [4.0e-3, 4.0e-3, 3.0e-3]}}
detonation: {points: [{position: [-4.0e-3, 0, 0], time: 0}]}
)";
    const Scenario sc = parse_deck(deck, "gas_measure.yaml");
    auto made = make_solver(sc);
    auto& solver = dynamic_cast<PdSolver&>(*made);
    FieldStore& pts = solver.points();
    const Index n = pts.size();
    auto* x = pts.view<Vec3>("x");
    const auto* mat = pts.ints("material");
    const double lambda = 1.3;
    for (Index p = 0; p < n; ++p) x[p] = lambda * x[p];
    std::vector<std::uint8_t> gas(static_cast<size_t>(n));
    for (Index p = 0; p < n; ++p) gas[p] = mat[p] == 0;
    const pd::BondFamily fam =
        pd::build_gas_family(pts.view<Vec3>("x0"), n, solver.horizon(), 1.0e-3, three ? 3 : 2, gas.data());
    std::vector<double> V(static_cast<size_t>(n), 0.0), g(static_cast<size_t>(n), 0.0);
    const auto* vol0 = pts.real("volume0");
    for (Index p = 0; p < n; ++p) {
      for (Index k = fam.offset[p]; k < fam.offset[p + 1]; ++k) V[p] += fam.volume_factor[k] * vol0[fam.other[k]];
      g[p] = gas[p] ? 1.0e9 * (1.0 + 0.01 * p) : 0.0;  // arbitrary, different pressures
    }
    const pd::GasPassArgs a{x, vol0, &fam, gas.data(), V.data(), g.data(), three ? 3 : 2};
    double worst = 0.0, fmax = 0.0;
    Vec3 total;
    for (Index p = 0; p < n; ++p) {
      if (gas[p]) worst = std::max(worst, std::abs(pd::density_measure(a, p) / std::pow(lambda, three ? 3 : 2) - 1.0));
      const Vec3 f = pd::gas_force(a, p);
      total += f;
      fmax = std::max(fmax, norm(f));
    }
    EXPECT_LT(worst, 1e-12) << dim;
    EXPECT_LT(norm(total), 1e-12 * fmax * static_cast<double>(n)) << dim;
  }
}

// An ideal-gas charge released from rest (issue 15 item 5): a disc of gamma = 3 products (rho0
// 1630, D 6930, volume burn at once: burn_cells 0), radius 10 mm, lit at its centre, expands
// freely (plane strain). Each point lights at X = 1 with E = Q and then follows its isentrope
// E X^(gamma-1) = Q, so the work the gas has done, which is its kinetic energy, is
// sum_p Q (1 - X_p^(1-gamma)) V0_p with each point's own density measure X_p (F = X^(1/2) I):
// a prediction of the kinetic energy from the points' expansions alone. Measured +0.04 % at 0.5 mm
// (worst residual 0.3 %); bound 3 %, the MPM test's: what can separate the two is the gas
// compressed behind the diverging front before it expands and the explicit step's error. The energy balance closes
// to 2 % of the chemical energy (the issue's bound).
TEST(PdGas, IdealGasExpandsWithTheWorkOfItsIsentropes) {
  const Scenario sc = parse_deck(R"(
simulation: {solver: peridynamics, dimension: plane_strain, end_time: 6.0e-6}
materials:
  gas: {model: explosive, density: 1630, detonation_speed: 6930, products: ideal_gas, gamma: 3}
grid: {lower: [-0.08, -0.08], upper: [0.08, 0.08], cell_size: 0.5e-3}
bodies:
  - {name: charge, material: gas, shape: {type: cylinder, center: [0, 0, 0], axis: z, radius: 10.0e-3}}
detonation: {points: [{position: [0, 0], time: 0}], burn_cells: 0}
)",
                                 "pd_ideal_gas.yaml");
  auto solver = make_solver(sc);
  const double worst = verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
  const EnergyTotals e = solver->energies();
  const double Q = detonation_energy(ideal_gas_products(1630.0, 6930.0, 3.0));
  const FieldStore& pts = solver->points();
  const auto* F = pts.view<Mat3>("F");
  const auto* vol0 = pts.real("volume0");
  const auto* burnt = pts.real("burn_fraction");
  double isentrope_work = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    ASSERT_EQ(burnt[p], 1.0);  // 10 mm at 6.93 km/s: burnt by 1.5 us
    isentrope_work += Q * (1.0 - std::pow(det(F[p]), -2.0)) * vol0[p];
  }
  EXPECT_EQ(result(*solver, "vented_gas_points"), 0.0);  // the box holds the whole cloud
  std::printf("PD ideal-gas expansion: kinetic energy %.6g J/m, isentropes' work %.6g J/m (%.2f %%), worst "
              "residual %.4f of the chemical energy %.6g J/m\n",
              e.kinetic, isentrope_work, 100.0 * (e.kinetic / isentrope_work - 1.0), worst / e.chemical, e.chemical);
  EXPECT_NEAR(e.kinetic / isentrope_work, 1.0, 0.03);
  EXPECT_LT(worst / e.chemical, 0.02);
}

/// The Gurney cylinder deck (plane strain: an infinitely long charge lit along its axis), PD;
/// `more` adds keys to the peridynamics section (", key: value").
std::string cylinder_deck(double mc, double h, double end, double box, const char* more = "") {
  const double a = 10.0e-3, b = gurney::case_radius(mc, a);  // M = (M/C) C per length
  char buf[1536];
  std::snprintf(buf, sizeof buf, R"(
simulation: {solver: peridynamics, dimension: plane_strain, end_time: %g}
peridynamics: {m: 3, yield_stress: 1.0e6%s}
materials:
  tnt: {preset: tnt}
  steel: {model: linear_elastic, density: 7850, bulk_modulus: 160.0e9, shear_modulus: 79.0e9}
grid: {lower: [-%g, -%g], upper: [%g, %g], cell_size: %g}
bodies:
  - {name: charge, material: tnt, shape: {type: cylinder, center: [0, 0, 0], axis: z, radius: %.9g}}
  - {name: case, material: steel, shape: {type: tube, center: [0, 0, 0], axis: z, radius: %.9g, inner_radius: %.9g}}
detonation: {points: [{position: [0, 0], time: 0}]}
)",
                end, more, box, box, box, box, h, a, b, a);
  return buf;
}

// The Gurney cylinder with the peridynamic gas (Gurney 1943; Cooper 1996 ch. 27):
// V = sqrt(2E) (M/C + 1/2)^(-1/2), TNT's sqrt(2E) = 2440 m/s, a strengthless case (micro-plastic
// bonds yielding at 1 MPa), read at 20 us as in the MPM test (test_gurney.cpp). The products push
// the case through the gas bonds of the reference neighbourhood and, for gas arriving from deeper
// in the charge, through the case's contact springs (without them the gas streams through the case
// and it reaches half the velocity). Bound 10 % (the issue's). Measured at 0.5 mm: +0.5 % (M/C 1),
// +6.0 % (M/C 2), worst energy residual 1.5 % / 0.9 % (bound 2 %, the issue's). With the reference
// family the case does NOT converge in h: 1 mm gives -16 % / -8 %, 0.25 mm +10 % / +13 %, 0.125 mm
// +15 % / +16 %, beyond the continuum's +4 % / +3 % (next test), with 0.99 of the chemical energy
// kinetic at 20 us where the continuum has 0.71-0.76. The renewed family converges (next test).
// This test holds the 0.5 mm figures of the reference family, not a convergence claim.
TEST(PdGas, GurneyCylinder) {
  for (double mc : {1.0, 2.0}) {
    const Scenario sc = parse_deck(cylinder_deck(mc, 0.5e-3, 20.0e-6, 0.08), "pd_gurney_cylinder.yaml");
    auto solver = make_solver(sc);
    const double worst = verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
    const auto* body = solver->points().ints("body");
    const double V = verification::mean_radial_velocity(solver->points(), false, [&](Index p) { return body[p] == 1; });
    const double gurney = gurney_cylinder(2440.0, mc);
    const EnergyTotals e = solver->energies();
    std::printf("PD Gurney cylinder, M/C = %.1f: case %.0f m/s, Gurney %.0f m/s (%+.1f %%), residual %.4f of the "
                "chemical energy\n",
                mc, V, gurney, 100.0 * (V / gurney - 1.0), worst / e.chemical);
    EXPECT_NEAR(V / gurney, 1.0, 0.10) << mc;
    EXPECT_LT(worst / e.chemical, 0.02) << mc;
  }
}

/// The same cylinder in axisymmetric MPM (continuum products; gurney_cylinder_support.hpp).
double mpm_cylinder_velocity(double mc, double h) {
  const Scenario sc = parse_deck(gurney::mpm_cylinder_deck(mc, h), "mpm_gurney_cylinder.yaml");
  auto solver = make_solver(sc);
  verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
  const auto* body = solver->points().ints("body");
  return verification::mean_radial_velocity(solver->points(), true, [&](Index p) { return body[p] == 1; });
}

// With the gas family renewed in the current configuration (gas_refamily_steps, as the exploding
// cylinder runs it) the peridynamic case converges to the continuum's. The reference is the same
// cylinder in axisymmetric MPM at 0.25 mm, itself converged: 1893, 2011, 2058 and 2068 m/s at
// 1, 0.5, 0.25 and 0.125 mm for M/C 1 (+3.9 % over Gurney's 1992 m/s, whose linear velocity
// profile is an approximation). The renewed family (runs of the deck with output every 5 us,
// validation/gas_family_convergence.py), M/C 1: 1834, 1978 and 2062 m/s at 0.5, 0.25 and 0.125 mm,
// -11.3 %, -4.3 % and -0.3 % of MPM's 0.125 mm (M/C 2: -4.4 %, -2.0 %, +0.8 %); kinetic energy 0.79 of the
// chemical, the continuum's 0.76. Here, stepped without output stops: 1810 and 1985 m/s, -12.0 %
// and -3.5 % of MPM's 0.25 mm. Bound: within 5 % at 0.25 mm, the error at least halved from 0.5 mm
// (measured 3.4x smaller), the residual under 2 % (the issue's; measured 0.3-0.4 %). M/C 1 only:
// each PD run of M/C 2 takes 40 % longer.
TEST(PdGas, RenewedFamilyCylinderConvergesToTheContinuum) {
  const double mpm = mpm_cylinder_velocity(1.0, 0.25e-3);
  double err[2];
  for (int level = 0; level < 2; ++level) {
    const double h = level == 0 ? 0.5e-3 : 0.25e-3;
    const Scenario sc =
        parse_deck(cylinder_deck(1.0, h, 20.0e-6, 0.08, ", gas_refamily_steps: 5"), "pd_gurney_cylinder.yaml");
    auto solver = make_solver(sc);
    const double worst = verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
    const auto* body = solver->points().ints("body");
    const double V = verification::mean_radial_velocity(solver->points(), false, [&](Index p) { return body[p] == 1; });
    err[level] = V / mpm - 1.0;
    std::printf("PD renewed family, M/C 1, %.2f mm: case %.0f m/s, MPM (0.25 mm) %.0f m/s (%+.1f %%), residual %.4f\n",
                h * 1e3, V, mpm, 100.0 * err[level], worst / solver->energies().chemical);
    EXPECT_LT(worst / solver->energies().chemical, 0.02);
  }
  EXPECT_LT(std::abs(err[1]), 0.05);
  EXPECT_LT(std::abs(err[1]), 0.5 * std::abs(err[0]));
}

// Gas that leaves the box is vented (issue 15 item 8): its kinetic and internal energy and momentum
// are booked as removed, the run goes on to the end without a NaN, and the balance still closes.
/// The ideal-gas disc (gamma = 3, 0.5 mm lattice, lit at its centre) of radius `radius` in a square
/// box of half-width `half_box`, run to `end_time`; `pd` holds extra peridynamics keys. Returns the
/// solver and the worst energy residual over the run over the chemical energy.
std::pair<std::unique_ptr<Solver>, double> run_gas_disc(double radius, double half_box, double end_time,
                                                       const std::string& pd) {
  const std::string h = std::to_string(half_box);
  const Scenario sc = parse_deck("simulation: {solver: peridynamics, dimension: plane_strain, end_time: " +
                                     std::to_string(end_time) + "}\n" + (pd.empty() ? "" : "peridynamics: {" + pd + "}\n") +
                                     R"(materials:
  gas: {model: explosive, density: 1630, detonation_speed: 6930, products: ideal_gas, gamma: 3}
grid: {lower: [-)" + h + ", -" + h + "], upper: [" + h + ", " + h + R"(], cell_size: 0.5e-3}
bodies:
  - {name: charge, material: gas, shape: {type: cylinder, center: [0, 0, 0], axis: z, radius: )" +
                                     std::to_string(radius) + R"(}}
detonation: {points: [{position: [0, 0], time: 0}]}
)",
                                 "pd_gas_disc.yaml");
  auto solver = make_solver(sc);
  const double worst = verification::run_worst_energy_residual(*solver, end_time);
  return {std::move(solver), worst / solver->energies().chemical};
}

// The ideal-gas disc of the test above in a box only 3 radii wide: 832 of 1264 points vented,
// removed energy 24 % of the chemical, worst residual 1.6 % (bound 2 %, the issue's).
TEST(PdGas, GasLeavingTheBoxIsVentedWithItsEnergyBooked) {
  const auto [solver, worst] = run_gas_disc(10.0e-3, 0.015, 10.0e-6, "");
  const EnergyTotals e = solver->energies();
  const double vented = result(*solver, "vented_gas_points");
  std::printf("vented %.0f of %ld gas points; removed energy %.4g J/m of the chemical %.4g J/m; worst residual %.4f\n",
              vented, static_cast<long>(solver->points().size()), e.removed_energy, e.chemical, worst);
  EXPECT_GT(vented, 0.1 * static_cast<double>(solver->points().size()));
  EXPECT_GT(e.removed_energy, 0.1 * e.chemical);
  EXPECT_LT(worst, 0.02);
}

// Products renewed in the current configuration spread until a gas point's renewed family is empty
// (its neighbours are beyond delta min(s_p, s_q), s capped at 2.5). Such a point measures nothing
// and pushes nothing, so it keeps its X: read as X = 1 it was recompressed to its reference
// density, its -P dV booked as internal energy that nothing did (the exploding cylinder's audit
// reached 38 % of the chemical energy at 100 us; this disc stopped at 16 us on the non-finite
// stress of a recompressed point). The bound is the vented test's 2 %.
TEST(PdGas, LoneGasPointsKeepTheirDensityAndTheAuditCloses) {
  const auto [solver, worst] = run_gas_disc(5.0e-3, 0.3, 30.0e-6, "gas_refamily_steps: 2");
  const double lone = result(*solver, "lone_gas_points");
  std::printf("lone %.0f of %ld gas points, vented %.0f; worst residual %.4f of the chemical energy\n", lone,
              static_cast<long>(solver->points().size()), result(*solver, "vented_gas_points"), worst);
  EXPECT_GT(lone, 0.05 * static_cast<double>(solver->points().size()));  // the path is exercised
  EXPECT_LT(worst, 0.02);
}

}  // namespace
}  // namespace ballista::test_pd_gas
