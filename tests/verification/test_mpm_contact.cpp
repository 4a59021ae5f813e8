// Multi-velocity-field contact on the MPM grid (issue 13; Bardenhagen et al. 2000, 2001;
// src/mpm/grid_contact.hpp) against closed forms:
//  - a block sliding on a floor under gravity decelerates at mu g (Coulomb), and keeps its speed
//    without friction;
//  - two identical elastic bars meeting head-on at +-v0 (uniaxial strain) separate after the
//    contact time 2 L / c with their velocities reversed, without sticking and without
//    interpenetrating, and total momentum is conserved exactly;
//  - a strengthless rod into a strengthless target, frictionless, penetrates at the hydrodynamic
//    rate U_h = V / (1 + sqrt(rho_t / rho_p)) (Birkhoff et al. 1948; thesis seed 000 ch. 3).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "deck/deck_reader.hpp"
#include "points/solver_registry.hpp"
#include "verification/verification_support.hpp"

namespace test_mpm_contact {

using namespace ballista;
using namespace ballista::verification;

struct BodyState {
  double mass = 0.0;
  Vec3 momentum;
  double xmin = 1e300, xmax = -1e300;  ///< extent of the particle centres along x, m
  Vec3 velocity() const { return (1.0 / mass) * momentum; }
};

BodyState body_state(Solver& s, int body) {
  FieldStore& pts = s.points();
  const auto* b = pts.ints("body");
  const auto* m = pts.real("mass");
  const auto* v = pts.view<Vec3>("v");
  const auto* x = pts.view<Vec3>("x");
  BodyState st;
  for (Index p = 0; p < pts.size(); ++p) {
    if (b[p] != body) continue;
    st.mass += m[p];
    st.momentum += m[p] * v[p];
    st.xmin = std::min(st.xmin, x[p][0]);
    st.xmax = std::max(st.xmax, x[p][0]);
  }
  return st;
}

// Soft neo-Hookean solid: rho 1000, E 10 MPa, nu 0.3; P-wave modulus E(1-nu)/((1+nu)(1-2nu)).
constexpr double kRho = 1000.0, kE = 1.0e7, kNu = 0.3;
const double kCp = std::sqrt(kE * (1 - kNu) / ((1 + kNu) * (1 - 2 * kNu)) / kRho);  // 116.0 m/s

const char* kSlide = R"(
simulation: {solver: mpm, dimension: plane_strain, end_time: 0.2, cfl: 0.3}
materials:
  soft: {model: neo_hookean, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
mpm: {shape_function: gimp, update: musl, flip: 1.0}
grid: {lower: [0.0, 0.0], upper: [0.6, 0.1], cell_size: 0.01, boundary: {y_min: fixed}}
bodies:
  - {name: floor, material: soft, shape: {type: box, lower: [0.0, 0.0], upper: [0.6, 0.04]}}
  - {name: block, material: soft, shape: {type: box, lower: [0.1, 0.04], upper: [0.3, 0.08]}, velocity: [1.0, 0]}
loads:
  - {type: gravity, direction: [0, -1]}
contact: {model: friction, friction: 0.3}
)";

const char* kBars = R"(
simulation: {solver: mpm, dimension: plane_strain, end_time: 6.0e-3, cfl: 0.3}
materials:
  soft: {model: neo_hookean, density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
mpm: {shape_function: gimp, update: musl, flip: 1.0}
grid: {lower: [0.0, 0.0], upper: [0.6, 0.02], cell_size: 0.005, boundary: {y_min: symmetry, y_max: symmetry}}
bodies:
  - {name: left, material: soft, shape: {type: box, lower: [0.1, 0.0], upper: [0.25, 0.02]}, velocity: [2.0, 0]}
  - {name: right, material: soft, shape: {type: box, lower: [0.255, 0.0], upper: [0.405, 0.02]}, velocity: [-2.0, 0]}
contact: {model: friction, friction: 0}
)";

const char* kHydro = R"(
simulation: {solver: mpm, dimension: axisymmetric, end_time: 26.0e-6, cfl: 0.3, on_particle_exit: delete}
mpm: {shape_function: gimp, update: musl, flip: 0.99}
grid: {lower: [0.0, -2.0e-3], upper: [16.0e-3, 62.0e-3], cell_size: 0.5e-3, boundary: {x_min: symmetry}}
materials:
  rod_fluid: {model: j2_plasticity, density: 7850, bulk_modulus: 160.0e9, shear_modulus: 80.0e9, yield_stress: 1.0e3}
  target_fluid: {model: j2_plasticity, density: 2700, bulk_modulus: 70.0e9, shear_modulus: 26.0e9, yield_stress: 1.0e3}
bodies:
  - {name: target, material: target_fluid, shape: {type: cylinder, center: [0, 0], axis: y, radius: 15.0e-3, length: 40.0e-3}}
  - name: rod
    material: rod_fluid
    rod: {nose: [0, 40.5e-3], axis: y, direction: -1, diameter: 4.0e-3, length: 20.0e-3, speed: 1500}
contact: {model: friction, friction: 0}
penetration: {penetrator: rod, target: target}
output: {interval: 0, history_every: 5}
)";

TEST(MpmContact, SlidingBlockDeceleratesAtMuG) {
  // Coulomb sliding: the floor's normal force is the block's weight, so dv/dt = -mu g while it
  // slides (v0 = 1 m/s, mu g = 2.94 m/s^2: it stops at 0.34 s, after the run). The slope is taken
  // between 0.05 s (the block has settled on the floor: the gravity loading wave has crossed it
  // ~30 times) and 0.15 s. Measured: 3.06 m/s^2 at h = 10 mm (+4.0 %) and 2.99 m/s^2 at h = 5 mm
  // (+1.6 %; slopes over 0.05-0.2 s): the excess converges with the grid (the block's corners plough: their contact
  // normals tilt), so 6 % bounds the CI resolution.
  const double mu = 0.3, g = 9.814;
  Scenario sc = parse_deck(kSlide, "slide.yaml");
  ASSERT_EQ(sc.contact.fields, 2);
  std::unique_ptr<Solver> s = make_solver(sc);
  const EnergyTotals e0 = s->energies();
  advance(*s, 0.05);
  const double v1 = body_state(*s, 1).velocity()[0];
  advance(*s, 0.15);
  const double v2 = body_state(*s, 1).velocity()[0];
  const double decel = (v1 - v2) / 0.1;
  std::printf("sliding block: deceleration %.4f m/s^2, mu g = %.4f (ratio %.4f)\n", decel, mu * g, decel / (mu * g));
  report("slide_decel_over_mu_g", decel / (mu * g));
  EXPECT_NEAR(decel / (mu * g), 1.0, 0.06);
  // Friction work booked: the residual of the energy balance stays small (measured 0.49 % of the
  // initial kinetic energy with the impulses booked at the step's midpoint, 0.66 % with each
  // pass's own; bound 1 %). The frictional part, booked with the same midpoint, is -2.689 J of the
  // -2.679 J contact work: the normal impulses add +0.01 J (the floor also pushes the settling
  // block back up).
  const EnergyTotals e = s->energies();
  EXPECT_LT(e.contact, 0.0);
  EXPECT_LT(e.friction, 0.0);
  std::printf("sliding block: contact work %.4e J, friction %.4e J, external %.4e J, residual %.4e J of KE0 %.4e J\n",
              e.contact, e.friction, e.external, e.total() - e0.total(), e0.kinetic);
  EXPECT_LT(std::abs(e.total() - e0.total()), 0.01 * e0.kinetic);

  // Without friction the block keeps sliding: measured 0.944 m/s after 0.2 s (the corners'
  // ploughing again: 0.095 mu g; 0.955 m/s after 0.1 s); with mu = 0.3 it would be 0.71 m/s.
  Scenario sc0 = parse_deck(kSlide, "slide.yaml", {"contact.friction=0"});
  std::unique_ptr<Solver> s0 = make_solver(sc0);
  advance(*s0, 0.1);
  const double v0 = body_state(*s0, 1).velocity()[0];
  std::printf("frictionless block: %.4f m/s after 0.1 s\n", v0);
  EXPECT_GT(v0, 0.93);
}

// The two bars of kBars run to 6 ms under one update scheme (mpm.update).
struct BarsRun {
  BodyState a, b;
  double p0 = 0.0, worst_overlap = -1e300, contact_end = 0.0;
  EnergyTotals e0, e;
};

BarsRun run_bars(const std::string& update, const std::vector<std::string>& sets = {}) {
  std::string deck = kBars;
  deck.replace(deck.find("update: musl"), 12, "update: " + update);
  Scenario sc = parse_deck(deck, "bars.yaml", sets);
  std::unique_ptr<Solver> s = make_solver(sc);
  BarsRun r;
  r.p0 = body_state(*s, 0).momentum[0] + body_state(*s, 1).momentum[0];
  r.e0 = s->energies();
  const double end = 6.0e-3;
  while (s->time() < end * (1 - 1e-12)) {
    s->step(std::min(s->stable_dt(), end - s->time()));
    const BodyState a = body_state(*s, 0), b = body_state(*s, 1);
    // Particle centres of the two bars are half a particle spacing (1.25 mm) from their faces.
    r.worst_overlap = std::max(r.worst_overlap, a.xmax - b.xmin);
    if (a.velocity()[0] > 0.0) r.contact_end = s->time();  // still moving right: not yet rebounded
  }
  r.a = body_state(*s, 0);
  r.b = body_state(*s, 1);
  r.e = s->energies();
  std::printf("bars (%s): rebound %.4f / %.4f m/s, contact ended by %.3e s (2L/c = %.3e s after first touch), "
              "closest centres %.3e m\n", update.c_str(), r.a.velocity()[0], r.b.velocity()[0], r.contact_end,
              2 * 0.15 / kCp, -r.worst_overlap);
  std::printf("bars (%s): kinetic + internal %.4f J (start %.4f J), contact work %.4f J, transfer %.4f J, "
              "residual %.4f of KE0\n", update.c_str(), r.e.kinetic + r.e.internal, r.e0.kinetic, r.e.contact,
              r.e.transfer, (r.e.total() - r.e0.total()) / r.e0.kinetic);
  return r;
}

// What holds for either update: momentum, rebound without sticking, no interpenetration, timing.
void expect_bars_rebound(const BarsRun& r, double speed_tolerance) {
  const double v0 = 2.0, L = 0.15;
  // Momentum: exact up to round-off (the contact impulses of a pair are equal and opposite).
  EXPECT_NEAR(r.a.momentum[0] + r.b.momentum[0], r.p0, 1e-12 * std::abs(r.a.momentum[0]));
  // Rebound, no sticking: both bars reversed and separating.
  EXPECT_NEAR(r.a.velocity()[0], -v0, speed_tolerance * v0);
  EXPECT_NEAR(r.b.velocity()[0], v0, speed_tolerance * v0);
  EXPECT_LT(r.a.xmax, r.b.xmin);
  // No interpenetration: the facing particle centres never cross (they start 7.5 mm apart; measured
  // closest 5.3 mm: grid contact acts once two fields share a node, so the faces stay ~half a cell
  // apart, the known gap of multi-field MPM contact).
  EXPECT_LT(r.worst_overlap, 0.0);
  // The mean velocity of a bar changes sign half-way through the contact, L / c after the first
  // touch; the 5 mm gap closes at 4 m/s by 1.25 ms (GIMP fields meet up to a cell earlier).
  EXPECT_GT(r.contact_end, L / kCp);
  EXPECT_LT(r.contact_end, 1.25e-3 + L / kCp);
}

TEST(MpmContact, ElasticBarsReboundAndSeparate) {
  // Two identical bars (L = 0.15 m) at +-2 m/s, uniaxial strain: the interface stops, a
  // compression wave runs to each free end and back, and the bars leave with -+2 m/s after
  // 2 L / c = 2.59 ms of contact (elementary wave theory). Measured at h = 5 mm: rebound speed
  // 2.079 m/s (+4.0 %; +3.6 % at 2.5 mm); kinetic + internal energy 15.7 J after separation against
  // 12 J before: MUSL's strain rate comes from the remapped velocity, nearly the next step's
  // mapped one, which makes it update-stress-first-like (energy grows: docs/validation.md,
  // "USAVG"); with USL the bars lose 1.1 J instead, with USAVG (next test) they keep it. The bound
  // of 6 % on the rebound speed is that measurement with margin.
  const BarsRun r = run_bars("musl");
  expect_bars_rebound(r, 0.06);
}

TEST(MpmContact, ElasticBarsKeepTheirEnergyUnderUsavg) {
  // The same collision with mpm.update usavg. Measured at h = 5 mm: rebound speed 2.004 m/s
  // (+0.2 %, against +4.0 % with MUSL); kinetic + internal 12.55 J after separation (+4.6 % of the
  // 12 J, where MUSL gains 31 % and USL loses 9.4 %), and the audit explains it: contact work
  // +1.15 J (the separating contact gives back more than the approach took), transfer -0.62 J,
  // residual 1.2e-3 of KE0 (MUSL 0.41). Bounds: 1 % on the rebound speed, 8 % on the energy after
  // separation, 1 % on the residual: the measurements with margin, each well below MUSL's.
  const BarsRun r = run_bars("usavg");
  expect_bars_rebound(r, 0.01);
  EXPECT_NEAR(r.e.kinetic + r.e.internal, r.e0.kinetic, 0.08 * r.e0.kinetic);
  EXPECT_LT(std::abs(r.e.total() - r.e0.total()), 0.01 * r.e0.kinetic);
}

TEST(MpmContact, ElasticBarsReboundWithTheGapCheck) {
  // contact.min_volume_fraction 0.25 (fields meet only where together they fill a quarter of the
  // node): the bars meet, rebound and separate as without the check. Measured: rebound 2.0798 m/s
  // against 2.0799 m/s without it (0.1: the same); at 0.5 the faces meet later, after the bars
  // have run into each other's nodes, and the rebound is 2.182 m/s (+9 %), beyond the MUSL bound.
  const BarsRun r = run_bars("musl", {"contact.min_volume_fraction=0.25"});
  expect_bars_rebound(r, 0.06);
}

// The strengthless rod of kHydro: U / U_h (least-squares rate between 6 and 26 us) and the worst
// energy residual.
std::pair<double, double> hydro_rate(const std::vector<std::string>& sets) {
  const double V = 1500.0, rho_p = 7850.0, rho_t = 2700.0;
  const double Uh = V / (1.0 + std::sqrt(rho_t / rho_p));
  TempDir dir("hydro");
  const RunResult r = run_into(parse_deck(kHydro, "hydro.yaml", sets), dir.str());
  EXPECT_TRUE(r.ok) << r.error;
  const History h = read_history(dir.str() + "/history.csv");
  const std::vector<double>& t = h["penetration_time"];
  const std::vector<double>& d = h["penetration_depth"];
  double n = 0, st = 0, sd = 0, stt = 0, std_ = 0;
  for (size_t k = 0; k < h.rows; ++k) {
    if (t[k] < 6.0e-6) continue;
    n += 1; st += t[k]; sd += d[k]; stt += t[k] * t[k]; std_ += t[k] * d[k];
  }
  EXPECT_GT(n, 10);
  const double U = (n * std_ - st * sd) / (n * stt - st * st);
  double worst = 0.0;
  for (double e : h["energy_drift"]) worst = std::max(worst, e);
  std::printf("strengthless rod: U = %.1f m/s, U_h = %.1f m/s, U/U_h = %.4f, worst energy residual %.4f\n", U, Uh,
              U / Uh, worst);
  return {U / Uh, worst};
}

TEST(MpmContact, StrengthlessRodPenetratesAtTheHydrodynamicRate) {
  // Steel-density rod (7850) at 1500 m/s into an aluminium-density target (2700), both with a
  // 1 kPa yield stress (strengthless) and stiff bulk moduli (the 1.2 GPa stagnation pressure
  // compresses them by < 2 %, so the incompressible Bernoulli balance holds):
  // U_h = V / (1 + sqrt(rho_t / rho_p)) = 945.5 m/s. The rate is the least-squares slope of the
  // depth between 6 and 26 us (the rod, 20 mm long, erodes at V - U = 555 m/s: it lasts 36 us).
  // Measured at 0.5 mm (4 cells across the rod's radius): U / U_h = 0.991 (frictionless fields),
  // 0.993 with one field; at 1 mm (2 cells) 0.928. The 3 % bound separates the resolved case from
  // the under-resolved one.
  const auto [rate, worst] = hydro_rate({});
  report("hydro_U_over_Uh", rate);
  EXPECT_NEAR(rate, 1.0, 0.03);
  // Energy audit: measured worst residual 0.005 (the PIC share of flip 0.99 and the contact work
  // booked); 2 % is the issue's bound for a verification problem.
  EXPECT_LT(worst, 0.02);
}

TEST(MpmContact, StrengthlessRodPenetratesAtTheHydrodynamicRateWithTheGapCheck) {
  // The same rod with the gap check (contact.min_volume_fraction 0.25): the rod's nose and the
  // crater's bottom fill the nodes they share, so the check leaves the penetration alone (same
  // bounds as above; measured U/U_h 0.9908 against 0.9909 without it, 0.989 at 0.5).
  const auto [rate, worst] = hydro_rate({"contact.min_volume_fraction=0.25"});
  EXPECT_NEAR(rate, 1.0, 0.03);
  EXPECT_LT(worst, 0.02);
}

TEST(MpmContact, StrengthlessRodPenetratesAtTheHydrodynamicRateWithTheDensityNormal) {
  // The same rod with the contact normal from the density gradient (contact.axisymmetric_normal:
  // density, tests/unit/mpm/test_contact_normal_axisymmetric.cpp), same bounds. Measured U/U_h
  // 0.9922 against 0.9909 with the ring mass's; at 1 mm (2 cells across the radius) 0.9415
  // against 0.9275: the rod's nose within a few cells of the axis meets the target along a
  // normal no longer tilted towards the axis.
  const auto [rate, worst] = hydro_rate({"contact.axisymmetric_normal=density"});
  EXPECT_NEAR(rate, 1.0, 0.03);
  EXPECT_LT(worst, 0.02);
}

}  // namespace test_mpm_contact
