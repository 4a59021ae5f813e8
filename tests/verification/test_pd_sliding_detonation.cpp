// A detonation sliding along a tube (issue 15 item 6: the exploding cylinder lit at one end): the
// peridynamic gas against the continuum. The products behind the front stream axially past the
// case; with the gas family fixed in the reference configuration they lose the case points they
// flow past and push the wall only through the contact springs, so the case is slow (docs/
// validation.md, "The exploding cylinder"). Renewing the gas family in the current configuration
// (peridynamics.gas_refamily_steps) restores the push. The reference is the same charge and case in
// axisymmetric MPM, whose products are a continuum (no family to lose): the case's mass-weighted
// radial velocity over the middle third of the tube at 25 us.
//
// Measured (2026-11-27): MPM 1547 m/s at 0.86 mm and at 0.43 mm (converged). Peridynamics at
// 1.72 mm (2 points through the wall, the example's box): fixed family 1367 m/s (-11.6 %), renewed
// every 5 steps 1467 m/s (-5.1 %); at 0.86 mm (the example) 1313 (-15 %) and 1491 m/s (-3.6 %).
// Bound 8 % at 1.72 mm (the coarse lattice's -5.1 % with room for the fracture pattern, which
// changes with round-off), and the renewal must gain at least 4 % over the fixed family (it gains
// 7.3 %; the fixed family fails the 8 % bound).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "verification/verification_support.hpp"

namespace ballista {
namespace {

constexpr double kLength = 98.0e-3;  // the example's tube (examples/exploding_cylinder_pd.yaml)

/// Mass-weighted radial velocity of body 0 (the case) over the middle third of the tube, m/s;
/// `axis` is the tube's axis (2: z in 3D, 1: y in axisymmetric runs, where x is the radius).
double middle_third_velocity(const FieldStore& pts, int axis) {
  const auto* x = pts.view<Vec3>("x");
  const auto* body = pts.ints("body");
  return verification::mean_radial_velocity(pts, axis == 1, [&](Index p) {
    return body[p] == 0 && x[p][axis] >= kLength / 3.0 && x[p][axis] < 2.0 * kLength / 3.0;
  });
}

/// The example's deck at lattice h with the gas family renewed every `renew_every` steps (0: fixed),
/// the charge on its own lattice `gas_spacing` (0: h). The example's box: with the box 11 mm beyond
/// the tube's ends, products vented while their neighbours still counted them gave a kinetic-energy
/// spike (+30 kJ in two steps, a residual of 5.6 % of the chemical energy on an AMD EPYC build, under
/// 2 % on the Intel Xeon of the earlier sessions); at 30 mm none (0.56 %).
std::string pd_deck(int renew_every, double h = 1.72e-3, double gas_spacing = 0.0) {
  const std::string spacing = gas_spacing > 0.0 ? ", point_spacing: " + std::to_string(gas_spacing) : "";
  return R"(
simulation: {solver: peridynamics, dimension: 3d, end_time: 25.0e-6}
peridynamics: {m: 3, yield_stress: 750e6, critical_stretch: 0.15, stretch_scatter: 0.1, gas_refamily_steps: )" +
         std::to_string(renew_every) + R"(}
materials:
  steel_4340: {model: linear_elastic, density: 7850, bulk_modulus: 140.3e9, shear_modulus: 70e9}
  pbxn9: {preset: lx14_pbxn9_standin}
grid: {lower: [-0.1, -0.1, -0.08], upper: [0.1, 0.1, 0.18], cell_size: )" + std::to_string(h) + R"(}
bodies:
  - {name: case, material: steel_4340, shape: {type: tube, center: [0, 0, 0], axis: z, radius: 16.13e-3, inner_radius: 12.7e-3, length: 98.0e-3}}
  - {name: charge, material: pbxn9, shape: {type: cylinder, center: [0, 0, 0], axis: z, radius: 12.7e-3, length: 98.0e-3})" +
         spacing + R"(}
detonation: {points: [{position: [0, 0, 0], time: 0}]}
)";
}

TEST(PdSlidingDetonation, RenewedGasFamilyPushesTheCaseLikeTheContinuum) {
  // The continuum reference: the same tube, charge and lighting in axisymmetric MPM; the case
  // yields at the same 750 MPa (J2) and does not fracture.
  const Scenario mpm = parse_deck(R"(
simulation: {solver: mpm, dimension: axisymmetric, end_time: 25.0e-6, cfl: 0.3, on_particle_exit: delete}
materials:
  steel_4340: {model: j2_plasticity, density: 7850, bulk_modulus: 140.3e9, shear_modulus: 70e9, yield_stress: 750e6}
  pbxn9: {preset: lx14_pbxn9_standin}
mpm: {shape_function: gimp, update: musl, flip: 0.99}
grid: {lower: [0.0, -0.03], upper: [0.07, 0.13], cell_size: 0.86e-3}
bodies:
  - {name: case, material: steel_4340, particles_per_cell: 2, shape: {type: tube, center: [0, 0, 0], axis: y, radius: 16.13e-3, inner_radius: 12.7e-3, length: 98.0e-3}}
  - {name: charge, material: pbxn9, particles_per_cell: 2, shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 12.7e-3, length: 98.0e-3}}
detonation: {points: [{position: [0, 0], time: 0}]}
)",
                                  "sliding_mpm.yaml");
  auto reference = make_solver(mpm);
  verification::run_worst_energy_residual(*reference, mpm.simulation.end_time);
  const double v_ref = middle_third_velocity(reference->points(), 1);

  double v[2];
  for (int renew : {0, 5}) {
    const Scenario sc = parse_deck(pd_deck(renew), "sliding_pd.yaml");
    auto solver = make_solver(sc);
    const double worst = verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
    v[renew ? 1 : 0] = middle_third_velocity(solver->points(), 2);
    std::printf("sliding detonation, PD 1.72 mm, gas family %s: middle third %.0f m/s, MPM continuum %.0f m/s "
                "(%+.1f %%), worst residual %.4f of the chemical energy\n",
                renew ? "renewed every 5 steps" : "fixed", v[renew ? 1 : 0], v_ref,
                100.0 * (v[renew ? 1 : 0] / v_ref - 1.0), worst / solver->energies().chemical);
    EXPECT_LT(worst / solver->energies().chemical, 0.02);  // issue 15's bound
  }
  EXPECT_NEAR(v[1] / v_ref, 1.0, 0.08);
  EXPECT_GT(v[1], 1.04 * v[0]);

  // The products on a lattice twice as coarse as the case (bodies[].point_spacing, the economy of
  // the example at 8 points through the wall): case 0.86 mm, gas 1.72 mm, renewed every 5 steps.
  // Measured 2026-11-27: 1476 m/s (-4.5 %), residual 0.4 %; the example's deck, whose steps also
  // land on its output times, gives 1513 m/s (-2.2 %) against 1491 m/s (-3.6 %) for the uniform
  // 0.86 mm lattice, in 30 s instead of 77 s. Same bound as above.
  const Scenario sc = parse_deck(pd_deck(5, 0.86e-3, 1.72e-3), "sliding_pd_coarse_gas.yaml");
  auto solver = make_solver(sc);
  const double worst = verification::run_worst_energy_residual(*solver, sc.simulation.end_time);
  const double vc = middle_third_velocity(solver->points(), 2);
  std::printf("sliding detonation, PD case 0.86 mm, gas 1.72 mm, renewed every 5 steps: middle third %.0f m/s "
              "(%+.1f %% against MPM), worst residual %.4f of the chemical energy\n",
              vc, 100.0 * (vc / v_ref - 1.0), worst / solver->energies().chemical);
  EXPECT_NEAR(vc / v_ref, 1.0, 0.08);
  EXPECT_LT(worst / solver->energies().chemical, 0.02);
}

}  // namespace
}  // namespace ballista
