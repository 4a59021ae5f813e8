// Peridynamics verification (issue 12, deliverable 4): the longitudinal wave speed of a thin bar
// and the energy released per unit area of new crack, for the bond-based PMB solver
// (src/peridynamics/pd_solver.cpp) at m = delta/dx = 3 with the partial-volume correction (the
// defaults). Write-up, tables and derivations: docs/validation.md, "Peridynamics: wave speed and
// energy release". The finer wave-speed level is in slow_pd_wave_speed.cpp (label slow).
//
// The reference values are not fitted: sqrt(E/rho) of the continuum, and the same expressions
// evaluated with the elastic constants and fracture energy of the discretised model on an infinite
// cubic lattice (lattice sums in pd_support.hpp, from the bond law alone, not from the solver). At
// fixed m the lattice quadrature of the horizon integral does not converge as delta -> 0 (Bobaru et
// al., IJNME 77 (2009) 852: delta-convergence at fixed m converges to the discrete model; only
// m -> infinity with it recovers the continuum), so the continuum error has a floor that these
// tests measure and assert separately.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "verification/pd_support.hpp"
#include "verification/verification_support.hpp"

namespace test_pd_wave_and_fracture {

using namespace ballista;
using namespace ballista::verification;

namespace {

// The lattice constants at m = 3 with the partial-volume rule (pd_support.hpp; also printed):
// C11 = 0.8649 x 9K/5, C12 = 0.9532 x 3K/5, E_100 = 0.8330 E (nu_100 = 0.2687), bulk 0.9002 K (the
// value of PdSolver.UniformDilatation...), fracture energy 0.8731 G0.
void print_lattice(const pdv::LatticeConstants& lc) {
  std::printf("lattice (m = 3, partial volumes): C11 %.4f, C12 %.4f, E_100 %.4f, nu_100 %.4f, K %.4f, G %.4f "
              "(ratios to the continuum)\n", lc.c11, lc.c12, lc.e100, lc.nu100, lc.k, lc.g);
}

}  // namespace

// Problem 1. A Gaussian velocity pulse (sigma = 6 mm) in a 4 x 4 x 96 mm bar, arrival (energy
// centroid) times at stations 24 mm apart. At dx = 1 and 0.5 mm (delta = 3 and 1.5 mm). Reference:
// the thin-bar speed sqrt(E/rho) (the section is 4 mm, the pulse ~ 36 mm long); for the discretised
// model, c_m = sqrt(E_100/rho) x (Rayleigh-Love factor, 0.9965) = 0.9095 c0 = 5203 m/s.
TEST(PdVerification, ThinBarWaveSpeedConvergesAtFirstOrderToTheLatticeBarSpeed) {
  const auto lc = pdv::lattice_constants(pdv::kM);
  print_lattice(lc);
  const pdv::BarGeometry g;
  const double c0 = std::sqrt(pdv::kE / pdv::kRho);
  const double cm = c0 * std::sqrt(lc.e100) * pdv::love_factor(g, lc.nu100);
  std::printf("c0 = sqrt(E/rho) = %.1f m/s; lattice bar speed c_m = %.1f m/s\n", c0, cm);
  const pdv::WaveStudy st = pdv::wave_study(g, cm, c0, "pd_wave");
  const double e0 = st.error_coarse, e1 = st.error_fine, p = st.order, c_ext = st.extrapolated;
  // The error is the bar's surface layer: points within delta of a face miss bonds (no surface
  // correction), so the bar is softer by a fraction ~ delta/w of its section: first order in dx at
  // fixed m. The PMB dispersion (group velocity c (1 - 0.06 k^2 delta^2), from the expansion of
  // the dispersion relation, Silling 2000 §6; 0.75 % at dx = 1 mm for this pulse) is second order and
  // smaller. The range 0.7-1.5 admits the pre-asymptotic coarse level (w = 1.33 delta) and rejects
  // no convergence (p ~ 0) and a spurious higher order.
  EXPECT_LT(e1, e0);
  EXPECT_GT(p, 0.7);
  EXPECT_LT(p, 1.5);
  // Finest error: measured 8.4 %; 10 % bounds the surface term at w = 2.67 delta (it halved from
  // 17.1 % at 1.33 delta) and still rejects a 10 % error in the bond constant c (5 % in speed on
  // top of the measured error).
  EXPECT_LT(e1, 0.10);
  // The extrapolated limit is the lattice bar speed: |c_ext/c_m - 1| = 0.3 % measured; 2 % allows the
  // unresolved second-order (dispersion) term, 0.75 % - 0.19 % at these levels, times 2^2/(2^2 - 1).
  EXPECT_NEAR(c_ext / cm, 1.0, 0.02);
  // Against the continuum sqrt(E/rho): the floor of the m = 3 lattice, sqrt(E_100/E) - 1 = -8.7 %,
  // plus the surface term: -16.7 % at dx = 0.5 mm, extrapolated -8.8 %. Bound 20 % at the finest
  // level (the floor and the halved surface term, 8.7 % + 8.4 %, plus margin) and 10 % extrapolated.
  EXPECT_LT(std::abs(st.levels[1].speed / c0 - 1), 0.20);
  EXPECT_LT(std::abs(c_ext / c0 - 1), 0.10);
}

// Problem 2a. Slow separation: a 24 mm cube (dx = 1 mm, delta = 3 mm, G0 = 8 J/m^2, s00 = 1.76e-4)
// pre-cracked over its mid-plane except a central 12 x 12 mm ligament; the halves are opened as
// rigid bodies through every critical opening of the lattice, so each crossing bond breaks at
// s0 (1 + 1e-7) and nothing else is stretched: the dissipated energy per ligament area is the
// model's fracture energy, Silling & Askari 2005 eq. 25 evaluated on the lattice.
TEST(PdVerification, SlowSeparationDissipatesTheLatticeFractureEnergy) {
  const auto lc = pdv::lattice_constants(pdv::kM);
  print_lattice(lc);
  const double g0 = 8.0;
  const pdv::FractureResult r = pdv::measure_fracture(1e-3, 24e-3, 12e-3, g0, true);
  std::printf("ligament %.0f mm^2: %ld crossing bonds, %ld broken, %ld off the plane; dissipated %.6e J\n",
              r.area * 1e6, r.crossing, r.broken_crossing, r.broken_off, r.dissipated);
  std::printf("G_measured / G0 = %.4f; the ligament's crossing bonds at s0 / G0 = %.4f; infinite lattice %.4f\n",
              r.g_measured / g0, r.g_lattice / g0, lc.g);
  report("pd_release_slow_G_over_G0", r.g_measured / g0);
  EXPECT_EQ(r.broken_crossing, r.crossing);
  EXPECT_EQ(r.broken_off, 0);  // rigid halves: no other bond is stretched
  // Each crossing bond dissipates its energy at s0 (1 + 1e-7): the sum to 1e-6.
  EXPECT_NEAR(r.g_measured / r.g_lattice, 1.0, 1e-6);
  // The ligament's crossing bonds against the infinite-lattice sum: the edges are placed off every
  // crossing point, so the two agree to round-off for a complete lattice family (the bond family
  // once lost bonds at exactly delta to bin round-off: 0.8633 vs 0.8731 then; 2e-9 now).
  EXPECT_NEAR(r.g_lattice / g0, lc.g, 1e-7);  // partial volumes are stored as float (6e-8 relative)
  // Against G0: eq. 25 integrates the crossing bonds over the continuum horizon; the lattice with the
  // LAMMPS partial-volume rule (bonds up to delta only) holds 0.873 of that integral, so with the
  // continuum constants G = 0.873 G0 (1.148 G0 without the correction).
  EXPECT_NEAR(r.g_measured / g0, lc.g, 1e-6);
}

// Problem 2a with the default `calibration: lattice`: s00 = sqrt(2 G0/(c m2)) from the lattice
// family's own moment (bond_family.hpp), so the slow separation dissipates G0 per unit of new
// crack area exactly (the target is 10 %; the remaining error is the 1e-7 overshoot of the
// openings and round-off).
TEST(PdVerification, SlowSeparationWithLatticeCalibrationDissipatesG0) {
  const double g0 = 8.0;
  const pdv::FractureResult r = pdv::measure_fracture(1e-3, 24e-3, 12e-3, g0, true, 0.0, 0.0, "lattice");
  std::printf("lattice calibration: G_measured / G0 = %.6f\n", r.g_measured / g0);
  report("pd_release_slow_lattice_G_over_G0", r.g_measured / g0);
  EXPECT_EQ(r.broken_crossing, r.crossing);
  EXPECT_EQ(r.broken_off, 0);
  EXPECT_NEAR(r.g_measured / g0, 1.0, 1e-6);
}

// Problem 2b. The same specimen torn dynamically: the halves get +-v, v = 0.5 s0 c0 (bulk strain
// v/c0 = 0.5 s0 would not break an unnotched block; the ligament concentrates it) and the ligament
// tears within 30 us. Every broken bond dissipates at least its energy at s0, so the dissipation is
// at least the crossing bonds' share; the excess is dynamic overshoot and bonds broken off the
// plane (a damage zone about one horizon wide). Energy is conserved by velocity Verlet.
TEST(PdVerification, DynamicTearDissipatesAtLeastTheLatticeFractureEnergy) {
  const double g0 = 8.0;
  const pdv::FractureResult r = pdv::measure_fracture(1e-3, 24e-3, 12e-3, g0, false, 0.5, 30e-6);
  std::printf("dynamic tear, v = 0.5 s0 c0, t = %.1f us: %ld of %ld crossing bonds broken, %ld off the plane\n",
              r.t_end * 1e6, r.broken_crossing, r.crossing, r.broken_off);
  std::printf("G_measured / G0 = %.4f (crossing bonds at s0: %.4f); initial kinetic %.3e J, dissipated %.3e J, "
              "energy change %+.2e of E0\n", r.g_measured / g0, r.dissipated_floor / r.area / g0, r.kinetic0, r.dissipated,
              r.energy_error);
  report("pd_release_dynamic_G_over_G0", r.g_measured / g0);
  // Nearly the whole ligament is torn (measured 98.7 %; the rest are bonds whose ends separate
  // together with a broken-off bit).
  EXPECT_GT(r.broken_crossing, 0.95 * r.crossing);
  EXPECT_GE(r.dissipated, r.dissipated_floor);
  EXPECT_GT(r.broken_off, 0);
  // The energy can only come from the initial kinetic energy.
  EXPECT_LT(r.dissipated, r.kinetic0);
  // Energy balance (kinetic + strain + dissipated). Without failure (G0 = 8e6 J/m^2, same velocity)
  // this run conserves it to 0.18 %. A bond breaking at x_{n+1} books its trapezoidal work over the
  // step, U(s_{n+1}) - 1/2 F (r_{n+1} - r_n) (pd_solver.cpp): booking U(s_{n+1}) alone made the total
  // grow by 7.4 % of E0 here. Bound 1 %: the sudden start's 0.18 % plus margin.
  EXPECT_LT(std::abs(r.energy_error), 0.01);
}

// Regression (src/peridynamics/bond_family.cpp): on a cubic lattice at m = 3 every interior point has
// 122 family members (30 at exactly delta). Search bins of exactly the horizon let two points delta
// apart along an axis round into bins two apart: 6,912 bond ends (of 1,455,112) of a 24^3 block were
// missing, e.g. p = (3.5, 0.5, 0.5) mm, q = p + (3, 0, 0) mm. The bins are now a hair wider.
TEST(PdVerification, BondFamilyOfALatticeHasEveryBondAtTheHorizon) {
  const double lo[3] = {0, 0, 0}, hi[3] = {24e-3, 24e-3, 24e-3};
  auto s = pdv::make_solver(pdv::box_deck(1e-3, lo, hi, "m: 3"));
  const auto* x0 = s->points().view<Vec3>("x0");
  const Index n = s->points().size();
  const auto& f = s->bonds();
  long missing = 0;
  for (Index p = 0; p < n; ++p) {
    const std::set<Index> row(f.other.begin() + f.offset[p], f.other.begin() + f.offset[p + 1]);
    for (Index q = 0; q < n; ++q) {
      const Vec3 d = x0[q] - x0[p];
      if (q != p && dot(d, d) <= 9e-6 * (1 + 2e-9) && !row.count(q)) ++missing;
    }
  }
  EXPECT_EQ(missing, 0);
}

}  // namespace test_pd_wave_and_fracture
