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

namespace test_b6_taylor_bar {

using namespace ballista;
using namespace ballista::verification;

TEST(B6TaylorBar, AxisymmetricWithinPublishedBands) {
  // cell_size 0.4 mm (2x2 particles per cell: 2592 particles, ~3200 steps, ~6 s on 2 cores); the
  // deck's 0.2 mm is in the slow suite. Measured: L_f 21.58 mm, R_f 7.15 mm, eqps 3.33.
  const Scenario sc = load_example("taylor_bar_mpm.yaml", {"grid.cell_size=0.4e-3"});
  const TaylorFigures f = run_taylor(sc, "taylor_axisym_h0.4mm");
  expect_in_acceptance_bands(f);

  // Initial kinetic energy = 1/2 m v0^2 of the analytic bar. In axisymmetry every particle carries
  // the per-radian volume r_p dr dz (times 2 pi when reported); the lattice tiles [0, R0] x [0, L0]
  // exactly (R0 and L0 are multiples of the 0.2 mm point spacing) and the midpoint rule integrates
  // r dr exactly, so the seeding error is zero and only round-off remains (measured 2e-15).
  EXPECT_NEAR(f.ke0, ke0_whole_bar(), 1e-12 * ke0_whole_bar());
  // Energy balance: no external work, so kinetic + internal (elastic + plastic) minus the booked
  // PIC share of the deck's FLIP/PIC blend (flip 0.99) and the booked boundary work (each step the
  // wall zeroes the inward velocity of its nodes, an inelastic impulse on that nodal mass;
  // total_energy, docs/deck.md "Energy audit") must stay at KE0 up to the time-integration error,
  // first order in h. Measured 0.88 % at 0.4 mm (1.6 % before the wall's impulses were booked,
  // 3.5 % before the PIC share was); bound 1.2 %, under issue 13's 2 % (0.39 % at the full 0.2 mm,
  // slow_b6_taylor_bar.cpp).
  EXPECT_LT(f.worst_balance, 0.012);
  // The bar has nearly stopped at 80 us: < 1 % of KE0 left (measured 0.06 %), so the figures are
  // measured at the end of the plastic flow, as in the FE references.
  EXPECT_LT(f.ke_end, 0.01 * f.ke0);
}

TEST(B6TaylorBar, UsavgClosesTheEnergyAudit) {
  // The same bar with mpm.update usavg (half the stress increment from the mapped grid velocity
  // before the forces, half from the updated one after; Nairn, CMES 4 (2003) 649), which books the
  // whole particle-grid transfer and the wall's impulses with the velocities whose strain rate the
  // stress halves see: the audit then closes up to the constitutive update's own integration.
  // Measured at 0.4 mm: residual 1.8e-4 of KE0 (3.0e-4 at 0.8 mm, 1.0e-4 at CFL 0.15), against
  // 0.88 % with USL above; L_f 21.58 mm, R_f 7.15 mm, eqps 3.36 (USL: 21.58, 7.15, 3.33). Bound
  // 1e-3: five times the measurement, and ten times below USL's.
  const Scenario sc = load_example("taylor_bar_mpm.yaml", {"grid.cell_size=0.4e-3", "mpm.update=usavg"});
  const TaylorFigures f = run_taylor(sc, "taylor_axisym_usavg_h0.4mm");
  expect_in_acceptance_bands(f);
  EXPECT_LT(f.worst_balance, 1e-3);
  EXPECT_LT(f.ke_end, 0.01 * f.ke0);
}

TEST(B6TaylorBar, ThreeDimensionalQuarterBarWithinPublishedBands) {
  // Quarter bar with two symmetry planes at cell_size 0.8 mm (2x2x2 particles per cell, 4212
  // particles, ~7 s on 2 cores). At 1.0 mm L_f is 22.16 mm, just outside the band, so 0.8 mm is
  // the coarsest 3D resolution that passes. Measured: L_f 21.90 mm, R_f 7.25 mm, eqps 2.77.
  const Scenario sc = load_example("taylor_bar_mpm_3d.yaml", {"grid.cell_size=0.8e-3"});
  const TaylorFigures f = run_taylor(sc, "taylor_3d_h0.8mm");
  expect_in_acceptance_bands(f);
  // Initial kinetic energy = 1/2 m_seeded v0^2 of the seeded quarter bar. The seeding keeps the
  // lattice points (i + 1/2) s, s = 0.4 mm, inside the bar: 81 layers cover L0 exactly, but the
  // quarter disk is a staircase of n_disk squares whose area differs from pi R0^2 / 4 by the
  // lattice-count error (+3.45 % here: 52 points where pi 8^2 / 4 = 50.3). With that count the
  // expected KE0 is exact up to round-off.
  const double s = 0.4e-3;
  long n_disk = 0;
  for (int i = 0; (i + 0.5) * s <= kR0; ++i)
    for (int k = 0; (k + 0.5) * s <= kR0; ++k)
      if (std::hypot((i + 0.5) * s, (k + 0.5) * s) <= kR0) ++n_disk;
  const double volume = static_cast<double>(n_disk) * s * s * kL0;
  const double ke0_lattice = 0.5 * kRho * volume * kV0 * kV0;
  const double ke0_quarter = 0.25 * ke0_whole_bar();
  report("taylor_3d_h0.8mm_quarter_disk_points", static_cast<double>(n_disk));
  report("taylor_3d_h0.8mm_KE0_seeding_error_rel", f.ke0 / ke0_quarter - 1.0);
  EXPECT_EQ(n_disk, 52);
  EXPECT_NEAR(f.ke0, ke0_lattice, 1e-12 * ke0_lattice);
  // Energy balance: the residual (see the axisymmetric test) falls about linearly with the cell
  // size: before the PIC share was booked 7.7 %, 5.9 %, 4.0 % at 0.8, 0.6, 0.4 mm (3D); with it
  // 3.6 % at 0.8 mm, and 2.3 % with the wall's and the symmetry planes' impulses booked too. At
  // this coarse size the bound is 4 %; the 5 % acceptance band is asserted at 0.4 mm in
  // slow_b6_taylor_bar.cpp.
  EXPECT_LT(f.worst_balance, 0.04);
  EXPECT_LT(f.ke_end, 0.01 * f.ke0);
}

}  // namespace test_b6_taylor_bar
