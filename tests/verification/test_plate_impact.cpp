// Symmetric copper plate impact (uniaxial strain) against the Rankine-Hugoniot jump conditions:
// the check of the artificial bulk viscosity (mpm.bulk_viscosity_*, src/mpm/bulk_viscosity.hpp).
//
// A 10 mm copper flyer at V = 2000 m/s hits a copper target at rest. By symmetry the shocked
// material moves at u_p = V / 2; with the linear Us-up Hugoniot of the copper preset (c0 = 3940
// m/s, s = 1.489) the shock runs at Us = c0 + s u_p = 5429 m/s into the target and at V - Us into
// the flyer, and the shocked state has J_H = 1 - u_p / Us = 0.8158 (mass and momentum jumps,
// e.g. Meyers, Dynamic Behavior of Materials (1994) eq. 4.4-4.5; the EOS's Hugoniot is
// tests/unit/materials/test_eos.cpp). Strength is switched off (jc_a 1 Pa, jc_b 0): a hydrodynamic
// shock. Until the flyer's shock reaches its free rear face (1.84 us) the exact velocity field is
// V | u_p | 0, separated by the two shocks.
//
// Measured (gimp, usavg, flip 0.99, 4 particles per cell, t = 1.5 us), L1 error of the particle
// velocity against that step profile, mass-weighted, over V:
//   h (mm)         1       0.5     0.25    0.125
//   no viscosity   0.0560  0.0472  0.0424  0.0337   (order 0.25, 0.16, 0.33: ringing)
//   C_L 0.2, C_Q 2 0.0417  0.0264  0.0158  0.0089   (order 0.66, 0.74, 0.83 -> 1)
// Without the viscosity the particles behind the shock ring (J 0.72-0.89 where J_H = 0.816, at
// 0.5 mm) and refining does not remove it; with it the profile converges towards first order,
// the order of a captured discontinuity in L1.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "deck/deck_reader.hpp"
#include "mpm/bulk_viscosity.hpp"
#include "points/solver_registry.hpp"
#include "verification/verification_support.hpp"

namespace test_plate_impact {

using namespace ballista;
using namespace ballista::verification;

namespace {

constexpr double kV = 2000.0, kC0 = 3940.0, kS = 1.489;  // copper_ofhc_jc's Hugoniot (data/materials.yaml)
constexpr double kUp = 0.5 * kV, kUs = kC0 + kS * kUp, kJH = 1.0 - kUp / kUs;
constexpr double kFace = 0.015;  // the impact plane at t = 0, m
constexpr double kEnd = 1.5e-6;  // s, before the flyer's shock reaches its rear face (1.84 us)

std::string plate_deck(double h, double linear, double quadratic, const std::string& update = "usavg",
                       const std::string& sound_speed = "current") {
  // Two cells across, symmetric faces: uniaxial strain.
  return fmt::format(R"(
simulation: {{solver: mpm, dimension: plane_strain, end_time: {end}, cfl: 0.3}}
materials:
  cu: {{preset: copper_ofhc_jc, jc_a: 1.0, jc_b: 0.0}}
mpm: {{shape_function: gimp, update: {update}, flip: 0.99, bulk_viscosity_linear: {cl}, bulk_viscosity_quadratic: {cq},
       bulk_viscosity_sound_speed: {speed}}}
grid: {{lower: [0.0, 0.0], upper: [0.05, {w}], cell_size: {h}, boundary: {{y_min: symmetry, y_max: symmetry}}}}
bodies:
  - {{name: flyer, material: cu, shape: {{type: box, lower: [0.005, 0.0], upper: [{face}, {w}]}}, velocity: [{V}, 0]}}
  - {{name: target, material: cu, shape: {{type: box, lower: [{face}, 0.0], upper: [0.045, {w}]}}}}
)",
                     fmt::arg("end", kEnd), fmt::arg("cl", linear), fmt::arg("cq", quadratic), fmt::arg("w", 2 * h),
                     fmt::arg("h", h), fmt::arg("face", kFace), fmt::arg("V", kV), fmt::arg("update", update),
                     fmt::arg("speed", sound_speed));
}

struct PlateRun {
  double l1_velocity = 0.0;   ///< mass-weighted L1 error of v_x against the step profile, / V
  double plateau_v = 0.0;     ///< mean v_x of the target's shocked plateau, m/s
  double plateau_J = 0.0;     ///< mean J there
  double shock_x = 0.0;       ///< where the target's J first exceeds (1 + J_H) / 2 from behind, m
  double residual = 0.0;      ///< |total - total0| / KE0
  double viscous = 0.0;       ///< viscous heating, J/m
};

PlateRun run_plate(double h, double linear, double quadratic, const std::string& update = "usavg",
                   const std::string& sound_speed = "current") {
  std::unique_ptr<Solver> s =
      make_solver(parse_deck(plate_deck(h, linear, quadratic, update, sound_speed), "plate.yaml"));
  const EnergyTotals e0 = s->energies();
  advance(*s, kEnd);
  FieldStore& pts = s->points();
  const auto* x = pts.view<Vec3>("x");
  const auto* v = pts.view<Vec3>("v");
  const auto* m = pts.real("mass");
  const auto* F = pts.view<Mat3>("F");
  const auto* body = pts.ints("body");
  const double t = s->time();
  const double back = kFace + (kV - kUs) * t, front = kFace + kUs * t;  // the two shocks now
  PlateRun r;
  double mass = 0.0, err = 0.0, np = 0.0;
  r.shock_x = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    const double xp = x[p][0];
    const double exact = xp < back ? kV : xp < front ? kUp : 0.0;
    err += m[p] * std::abs(v[p][0] - exact);
    mass += m[p];
    const double J = det(F[p]);
    // The plateau: the target's shocked material three cells clear of the contact face and the
    // shock (the viscosity spreads the jump over about three cells).
    if (body[p] == 1 && xp > kFace + kUp * t + 3 * h && xp < front - 3 * h) {
      r.plateau_v += v[p][0];
      r.plateau_J += J;
      np += 1.0;
    }
    if (body[p] == 1 && J < 0.5 * (1.0 + kJH)) r.shock_x = std::max(r.shock_x, xp);
  }
  r.l1_velocity = err / mass / kV;
  r.plateau_v /= np;
  r.plateau_J /= np;
  const EnergyTotals e = s->energies();
  r.residual = std::abs(e.total() - e0.total()) / e0.kinetic;
  r.viscous = e.viscous;
  std::printf("plate impact (%s) h = %.3g mm, C_L %.2g, C_Q %.2g: L1(v)/V %.4f, plateau v %.1f m/s (u_p %.1f), J %.4f "
              "(J_H %.4f), shock at %.3f mm (exact %.3f), residual %.2e of KE0, viscous heat %.4g J/m\n",
              update.c_str(), h * 1e3, linear, quadratic, r.l1_velocity, r.plateau_v, kUp, r.plateau_J, kJH, r.shock_x * 1e3,
              front * 1e3, r.residual, r.viscous);
  return r;
}

}  // namespace

TEST(PlateImpact, ShockedStateMatchesTheHugoniotAndConvergesWithBulkViscosity) {
  const double hs[3] = {1.0e-3, 0.5e-3, 0.25e-3};
  PlateRun av[3];
  for (int k = 0; k < 3; ++k) av[k] = run_plate(hs[k], 0.2, 2.0);
  const double p1 = observed_order(av[0].l1_velocity, av[1].l1_velocity);
  const double p2 = observed_order(av[1].l1_velocity, av[2].l1_velocity);
  std::printf("plate impact with bulk viscosity: observed L1 order %.2f (1 -> 0.5 mm), %.2f (0.5 -> 0.25 mm)\n", p1,
              p2);
  report("plate_impact_order_fine", p2);
  // Order: measured 0.66 and 0.74, rising towards the first order of a captured shock; 0.6 keeps
  // the rise and fails the ringing case (0.16 over the same pair).
  EXPECT_GT(p1, 0.6);
  EXPECT_GT(p2, 0.6);
  const PlateRun& fine = av[2];
  // The jump conditions at 0.25 mm: measured plateau v 997.5 m/s (-0.25 %) and J 0.8174 (+0.2 %:
  // the heat of the ringing the viscosity damps raises the EOS energy a little above the
  // Hugoniot's), the shock 0.16 mm behind Us t (particle centres). Bounds: 1 % on u_p and J_H, one
  // cell on the shock.
  EXPECT_NEAR(fine.plateau_v, kUp, 0.01 * kUp);
  EXPECT_NEAR(fine.plateau_J, kJH, 0.01 * kJH);
  EXPECT_NEAR(fine.shock_x, kFace + kUs * kEnd, hs[2]);
  // The audit closes with the viscous heat booked in the internal energy: measured 8.4e-4 of the
  // flyer's kinetic energy; without the viscosity 5.6e-3 (the ringing's transfer losses).
  EXPECT_LT(fine.residual, 2.0e-3);
  EXPECT_GT(fine.viscous, 0.0);

  // Without the viscosity the same run rings: its L1 error at 0.25 mm is 2.7 times larger (0.042
  // against 0.0158). A factor 2 is the bound.
  const PlateRun none = run_plate(hs[2], 0.0, 0.0);
  EXPECT_EQ(none.viscous, 0.0);
  EXPECT_GT(none.l1_velocity, 2.0 * fine.l1_velocity);
}

TEST(PlateImpact, BulkViscosityHelpsEveryUpdateScheme) {
  // The heat is booked with the q the forces used, which differs between the schemes (the
  // previous q with usl and musl, the first half's with usavg): the audit closes in each.
  // Measured at 0.5 mm, without -> with the viscosity: L1(v)/V usl 0.0427 -> 0.0259, musl 0.0491
  // -> 0.0279, usavg 0.0472 -> 0.0264; final residual (of KE0) usl 2.5e-2 -> 1.0e-2 (USL's own
  // loss), musl 5.8e-3 -> 3.8e-4, usavg 3.4e-3 -> 6.4e-4. Bounds: the error falls below 0.7 of the
  // ringing one and the residual does not grow, in each scheme.
  for (const char* update : {"usl", "musl", "usavg"}) {
    const PlateRun none = run_plate(0.5e-3, 0.0, 0.0, update);
    const PlateRun av = run_plate(0.5e-3, 0.2, 2.0, update);
    EXPECT_LT(av.l1_velocity, 0.7 * none.l1_velocity) << update;
    EXPECT_LT(av.residual, none.residual) << update;
    EXPECT_GT(av.viscous, 0.0) << update;
  }
}

TEST(PlateImpact, ReferenceSoundSpeedKeepsTheShockCapture) {
  // mpm.bulk_viscosity_sound_speed: reference takes the linear term's c at zero EOS energy. The
  // shocked copper's own energy (about p_H eta / 2 = 4.5 GJ/m^3 at 48.6 GPa) raises its sound speed
  // by a few per cent, so the capture is the same: measured L1(v)/V 0.0265 and 0.0160 at 0.5 and
  // 0.25 mm (0.0264 and 0.0158 with the current speed), order 0.73. Bounds: the order of the test
  // above (0.6) and the current speed's error within 5 %.
  const PlateRun coarse = run_plate(0.5e-3, 0.2, 2.0, "usavg", "reference");
  const PlateRun fine = run_plate(0.25e-3, 0.2, 2.0, "usavg", "reference");
  const PlateRun current = run_plate(0.25e-3, 0.2, 2.0);
  EXPECT_GT(observed_order(coarse.l1_velocity, fine.l1_velocity), 0.6);
  EXPECT_NEAR(fine.l1_velocity, current.l1_velocity, 0.05 * current.l1_velocity);
  EXPECT_NE(fine.l1_velocity, current.l1_velocity);  // the key is read, not ignored
  EXPECT_NEAR(fine.plateau_J, kJH, 0.01 * kJH);
  EXPECT_LT(fine.residual, 2.0e-3);
}

TEST(PlateImpact, PointsErodedToZeroStressCarryNoViscousPressure) {
  // The target fails at an equivalent plastic strain of 0.05 with zero_stress erosion (thesis eq.
  // 6.13-6.14): its failed points carry no stress, so no q either, while the compressing points
  // that have not failed do (measured at t = 1.5 us: 48 of 480 target points failed, q up to 1.7
  // GPa on the others and 7.5 GPa in the flyer).
  std::string deck = plate_deck(0.5e-3, 0.2, 2.0);
  const std::string target = "name: target, material: cu,";
  deck.replace(deck.find(target), target.size(), "name: target, material: cu_failing,");
  const std::string mat = "materials:\n";
  deck.insert(deck.find(mat) + mat.size(),
              "  cu_failing: {preset: copper_ofhc_jc, jc_a: 1.0, jc_b: 0.0, failure: {criterion: johnson_cook_damage, "
              "erosion: zero_stress, d1: 0.05, d2: 0, d3: 0, d4: 0, d5: 0}}\n");
  std::unique_ptr<Solver> s = make_solver(parse_deck(deck, "plate_failing.yaml"));
  advance(*s, kEnd);
  FieldStore& pts = s->points();
  const auto* body = pts.ints("body");
  const auto* failed = pts.real("failed");
  const auto* q = pts.real(kBulkViscosityField);
  int n_failed = 0;
  double q_failed = 0.0, q_intact = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    if (body[p] != 1) continue;
    if (failed[p] > 0.0) {
      ++n_failed;
      q_failed = std::max(q_failed, q[p]);
    } else {
      q_intact = std::max(q_intact, q[p]);
    }
  }
  EXPECT_GT(n_failed, 0);
  EXPECT_EQ(q_failed, 0.0);
  EXPECT_GT(q_intact, 1.0e8);
}

TEST(PlateImpact, BulkViscosityPressureAndSignalSpeedFollowTheirFormulas) {
  // q = rho l |tr D| (C_L c + C_Q l |tr D|) in compression, 0 in expansion; the Courant speed
  // Q + sqrt(Q^2 + c^2), Q = C_L c + C_Q l |tr D| (bulk_viscosity.hpp). Hand values: rho 8960,
  // c 4000, l 1e-3, tr D = -1e6 1/s: l |tr D| = 1000 m/s; q = 8960 * 1000 * (0.2 * 4000 + 2 * 1000)
  // = 2.5088e10 Pa; Q = 2800, speed = 2800 + sqrt(2800^2 + 4000^2) = 7682.68 m/s.
  const BulkViscosity bv{0.2, 2.0};
  EXPECT_NEAR(bulk_viscosity_pressure(bv, 8960.0, 4000.0, 1e-3, -1e6), 2.5088e10, 1e-6 * 2.5088e10);
  EXPECT_EQ(bulk_viscosity_pressure(bv, 8960.0, 4000.0, 1e-3, 1e6), 0.0);
  EXPECT_NEAR(bulk_viscosity_signal_speed(bv, 4000.0, 1e-3, -1e6), 2800.0 + std::sqrt(2800.0 * 2800.0 + 16e6), 1e-9);
  EXPECT_EQ(bulk_viscosity_signal_speed(bv, 4000.0, 1e-3, 1e6), 4000.0);
  // The linear term's speed apart from the point's (reference_sound_speed): with c_linear 1000,
  // q = 8960 * 1000 * (0.2 * 1000 + 2000) = 1.9712e10 Pa, Q = 2200, speed 2200 + sqrt(2200^2 + 4000^2).
  EXPECT_NEAR(bulk_viscosity_pressure(bv, 8960.0, 1000.0, 1e-3, -1e6), 1.9712e10, 1e-6 * 1.9712e10);
  EXPECT_NEAR(bulk_viscosity_signal_speed(bv, 4000.0, 1e-3, -1e6, 1000.0), 2200.0 + std::sqrt(2200.0 * 2200.0 + 16e6),
              1e-9);
  EXPECT_FALSE(BulkViscosity{}.active());
}

}  // namespace test_plate_impact
