// B6: copper Taylor anvil (OTM seed SAND2020-9716 ch. 4; CATALOGUE B6): rho 8930, E 117 GPa,
// nu 0.35, J2 with sigma_y0 400 MPa and linear hardening H 100 MPa, L0 32.4 mm, R0 3.2 mm,
// 227 m/s onto a rigid frictionless wall, 80 us. Final length, foot radius and peak equivalent
// plastic strain are checked against the acceptance bands of docs/validation.md (built from the
// published finite-element results collected there), plus the energy bookkeeping.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

using namespace ballista;
using namespace ballista::verification;

namespace {

constexpr double kRho = 8930.0, kR0 = 3.2e-3, kL0 = 32.4e-3, kV0 = 227.0;

/// Analytic initial kinetic energy of the whole bar, 1/2 rho pi R0^2 L0 v0^2 = 239.81 J.
double ke0_whole_bar() { return 0.5 * kRho * std::numbers::pi * kR0 * kR0 * kL0 * kV0 * kV0; }

double probe(const RunResult& r, const std::string& name) {
  for (const auto& [n, v] : r.probes)
    if (n == name) return v;
  ADD_FAILURE() << "no probe " << name;
  return NAN;
}

struct TaylorFigures {
  double L = 0, R = 0, eqps = 0;   // m, m, 1
  double ke0 = 0, mass0 = 0;       // J and kg of the simulated part (whole bar or quarter)
  double balance = 0;              // |E_total(end) - E_total(0)| / E_total(0)
  double worst_balance = 0;        // max over the history rows
  double ke_end = 0, internal_end = 0, plastic_end = 0;
  long steps = 0;
};

TaylorFigures run_taylor(const Scenario& sc, const char* tag) {
  TempDir dir(tag);
  const RunResult r = run_into(sc, dir.str());
  EXPECT_TRUE(r.ok) << r.error;
  const History h = read_history((dir.path() / "history.csv").string());
  TaylorFigures f;
  f.L = probe(r, "final_length");
  f.R = probe(r, "foot_radius");
  f.eqps = probe(r, "max_eqps");
  f.steps = r.steps;
  f.ke0 = h["kinetic_energy"].front();
  f.mass0 = h["mass"].front();
  const auto& E = h["total_energy"];
  f.balance = std::abs(E.back() - E.front()) / E.front();
  for (double e : E) f.worst_balance = std::max(f.worst_balance, std::abs(e - E.front()) / E.front());
  f.ke_end = h["kinetic_energy"].back();
  f.internal_end = h["internal_energy"].back();
  f.plastic_end = h["plastic_work"].back();
  std::printf("%s: %ld steps\n", tag, f.steps);
  report(std::string(tag) + "_final_length_mm", 1e3 * f.L);
  report(std::string(tag) + "_foot_radius_mm", 1e3 * f.R);
  report(std::string(tag) + "_max_eqps", f.eqps);
  report(std::string(tag) + "_KE0_J", f.ke0);
  report(std::string(tag) + "_KE_end_J", f.ke_end);
  report(std::string(tag) + "_internal_end_J", f.internal_end);
  report(std::string(tag) + "_plastic_work_end_J", f.plastic_end);
  report(std::string(tag) + "_energy_balance_end_rel", f.balance);
  report(std::string(tag) + "_energy_balance_worst_rel", f.worst_balance);
  return f;
}

/// Acceptance bands of docs/validation.md ("Taylor bar", recommended bands for an MPM run at
/// 80 us): the spread of the published FE results (L_f 21.42-21.48 mm, R_f 7.11-7.29 mm for the
/// sources read) widened by the expected MPM measurement offsets and locking (-2 %/+2.7 % on L_f,
/// -6 %/+5 % on R_f). eqps has no verified published value (diagnostic band 2.3-3.8).
void expect_in_acceptance_bands(const TaylorFigures& f) {
  EXPECT_GE(f.L, 21.0e-3);
  EXPECT_LE(f.L, 22.0e-3);
  EXPECT_GE(f.R, 6.8e-3);
  EXPECT_LE(f.R, 7.6e-3);
  EXPECT_GE(f.eqps, 2.3);
  EXPECT_LE(f.eqps, 3.8);
}

}  // namespace

TEST(B6TaylorBar, AxisymmetricWithinPublishedBands) {
  // cell_size 0.4 mm (2x2 particles per cell: 2592 particles, ~3200 steps, ~6 s on 2 cores); the
  // deck's 0.2 mm is in the slow suite. Measured: L_f 21.58 mm, R_f 7.15 mm, eqps 3.33.
  const Scenario sc = load_example("taylor_bar_mpm.yaml", {"grid.cell_size=0.4e-3"});
  const TaylorFigures f = run_taylor(sc, "taylor_axisym_h0.4mm");
  expect_in_acceptance_bands(f);

  // Initial kinetic energy = 1/2 m v0^2 of the analytic bar. In axisymmetry every particle carries
  // the per-radian volume r_p dr dz (times 2 pi when reported); the lattice tiles [0, R0] x [0, L0]
  // exactly (R0 and L0 are multiples of the 0.2 mm point spacing) and the midpoint rule integrates
  // r dr exactly, so the seeding error is zero and only round-off remains (measured 3e-16).
  EXPECT_NEAR(f.ke0, ke0_whole_bar(), 1e-12 * ke0_whole_bar());
  // Energy balance: no external work, so kinetic + internal (elastic + plastic) must stay at KE0
  // up to the energy the rigid-wall condition removes (each step it zeroes the inward velocity of
  // the wall nodes, an inelastic collision of the nodal mass, not a physical dissipation).
  // Measured 3.5 % at 0.4 mm; the bound is the 5 % acceptance band of docs/validation.md
  // (target band: 2 %).
  EXPECT_LT(f.worst_balance, 0.05);
  // The bar has nearly stopped at 80 us: < 1 % of KE0 left (measured 0.06 %), so the figures are
  // measured at the end of the plastic flow, as in the FE references.
  EXPECT_LT(f.ke_end, 0.01 * f.ke0);
}

TEST(B6TaylorBar, ThreeDimensionalQuarterBarWithinPublishedBands) {
  // Quarter bar with two symmetry planes at cell_size 0.8 mm (2x2x2 particles per cell, ~3.9k
  // particles, ~7 s on 2 cores). At 1.0 mm L_f is 22.16 mm, just outside the band, so 0.8 mm is
  // the coarsest 3D resolution that passes. Measured: L_f 21.90 mm, R_f 7.25 mm, eqps 2.77.
  const Scenario sc = load_example("taylor_bar_mpm_3d.yaml", {"grid.cell_size=0.8e-3"});
  const TaylorFigures f = run_taylor(sc, "taylor_3d_h0.8mm");
  expect_in_acceptance_bands(f);
  // Initial kinetic energy = 1/2 m_seeded v0^2 exactly (the seeded mass times v0^2, to round-off).
  EXPECT_NEAR(f.ke0, 0.5 * f.mass0 * kV0 * kV0, 1e-12 * f.ke0);
  // The seeded quarter disk is a staircase of 0.4 mm squares whose centres lie inside the circle;
  // its area differs from pi R0^2 / 4 by the lattice-count error (measured below); 3 % bounds it
  // for any point spacing <= 0.4 mm (the error is O(spacing / R0) in the worst case).
  const double ke0_quarter = 0.25 * ke0_whole_bar();
  report("taylor_3d_h0.8mm_KE0_seeding_error_rel", f.ke0 / ke0_quarter - 1.0);
  EXPECT_NEAR(f.ke0, ke0_quarter, 0.03 * ke0_quarter);
  EXPECT_LT(f.worst_balance, 0.05);
  EXPECT_LT(f.ke_end, 0.01 * f.ke0);
}
