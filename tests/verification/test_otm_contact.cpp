// OTM verification of the contact between bodies (otm.contact: pinball, src/otm/otm_contact.hpp):
// two identical elastic steel bars (axisymmetric, R = 5 mm, L = 50 mm, each with its own nodes)
// meet head-on at +-10 m/s. By symmetry the interface stays at rest: each bar behaves as the bar
// of test_otm_elastic_impact.cpp on a rigid wall. One-dimensional wave theory (Graff, Wave Motion
// in Elastic Solids, §2.1): contact for 2L/c_0, c_0 = sqrt(E/rho), then the bars separate with the
// speed they came with. Checks:
//  - the contact lasts 2L/c_0 within 5 % (first to last step with a pair in contact; measured
//    19.92 us against 19.81 us);
//  - the bars rebound and separate: each bar's mean velocity reversed, the same fraction of 10 m/s
//    as the one bar on the constraint wall within 2 % (the seed's "nearly equal" of its two wall
//    forms; measured 0.935 against the wall's, both below 1 by the vibration left in the bar);
//  - energy: (total - total_0) / KE_0 < 1 % after the contact, the springs' work booked as contact work;
//  - momentum: the two bars' momenta cancel to round-off (the pair forces are equal and opposite).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/point_fields.hpp"
#include "deck/deck_reader.hpp"
#include "otm/otm_solver.hpp"
#include "otm_steel_bar.hpp"
#include "run/simulation.hpp"

namespace ballista::test_otm_contact {
namespace {

constexpr double kRho = 7850.0, kE = 200.0e9, kL = 0.05, kV = 10.0, kEnd = 1.0e-4;

struct Bars {
  double first = -1.0, last = -1.0;  ///< s, first and last step with a pair in contact
  double residual = 0.0;             ///< (total - total0) / KE0 at the end
  double upper = 0.0, lower = 0.0;   ///< mean axial velocity of each bar at the end / kV
  double momentum = 0.0;             ///< total axial momentum / one bar's initial momentum
  double gap = 0.0;                  ///< m, the bars' closest points' distance at the end
};

Bars run_bars() {
  // The points sit on a 0.5 mm lattice from y = -60 mm: the bars' nearest points are 1.5 mm apart
  // (their balls' surfaces 1 mm), so they meet after 50 us.
  const std::string yaml = otm_steel_bar::head("1.0e-4") + R"(
otm: {contact: pinball}
grid: {lower: [0, -0.06], upper: [0.02, 0.06], cell_size: 1.0e-3, boundary: {x_min: symmetry}}
bodies:
  - {name: upper, material: steel, shape: {type: cylinder, center: [0, 0.0005, 0], axis: y, radius: 5.0e-3, length: 0.05},
     particles_per_cell: 2, velocity: [0, -10.0, 0]}
  - {name: lower, material: steel, shape: {type: cylinder, center: [0, -0.0505, 0], axis: y, radius: 5.0e-3, length: 0.05},
     particles_per_cell: 2, velocity: [0, 10.0, 0]}
)";
  const Scenario sc = parse_deck(yaml, "otm_contact_bars.yaml");
  OtmSolver s(sc, make_materials(sc));
  const EnergyTotals e0 = s.energies();
  Bars out;
  while (s.time() < kEnd) {
    const double t0 = s.time();
    s.step(s.stable_dt());
    if (s.history_values()[1] > 0.0) {
      if (out.first < 0.0) out.first = t0;
      out.last = s.time();
    }
  }
  const EnergyTotals e = s.energies();
  out.residual = (e.total() - e0.total()) / e0.kinetic;
  const FieldStore& P = s.points();
  const auto* body = P.ints(kBodyIndex);
  const auto* m = P.real(kMass);
  const auto* v = P.view(kVelocity);
  const auto* x = P.view(kPosition);
  double mv[2] = {0, 0}, mass[2] = {0, 0}, lowest_upper = 1.0, highest_lower = -1.0;
  for (Index p = 0; p < P.size(); ++p) {
    const int b = static_cast<int>(body[p]);
    mv[b] += m[p] * v[p][1];
    mass[b] += m[p];
    if (b == 0) lowest_upper = std::min(lowest_upper, x[p][1]);
    else highest_lower = std::max(highest_lower, x[p][1]);
  }
  out.upper = mv[0] / mass[0] / kV;
  out.lower = mv[1] / mass[1] / kV;
  out.momentum = (mv[0] + mv[1]) / (mass[0] * kV);
  out.gap = lowest_upper - highest_lower;
  return out;
}

double wall_rebound() {
  const Scenario sc = parse_deck(otm_steel_bar::on_wall("constraint", "3.0e-5"), "otm_wall_bar.yaml");
  OtmSolver s(sc, make_materials(sc));
  while (s.time() < 3.0e-5) s.step(s.stable_dt());
  const EnergyTotals e = s.energies();
  return e.momentum[1] / e.mass / kV;
}

TEST(OtmContact, ElasticBarsMeetReboundAndSeparate) {
  const double c0 = std::sqrt(kE / kRho), t_contact = 2.0 * kL / c0;
  const Bars b = run_bars();
  const double wall = wall_rebound();
  std::printf("bars: contact %.4g s (2L/c0 %.4g s), rebound %.4f / %.4f (wall %.4f), residual %.2e, momentum %.2e, "
              "gap %.3g m\n",
              b.last - b.first, t_contact, b.upper, b.lower, wall, b.residual, b.momentum, b.gap);
  EXPECT_NEAR(b.first, 1.0e-3 / (2.0 * kV), 0.05 * 50e-6);  // the balls' 1 mm gap closed at 20 m/s
  EXPECT_NEAR(b.last - b.first, t_contact, 0.05 * t_contact);
  EXPECT_GT(b.upper, 0.0);  // reversed: the upper bar came down at -10 m/s
  EXPECT_LT(b.lower, 0.0);
  EXPECT_NEAR(b.upper, wall, 0.02);
  EXPECT_NEAR(-b.lower, wall, 0.02);
  EXPECT_GT(b.gap, 0.75e-3);  // apart again: the nearest points 0.75 mm apart, their balls reach 0.5 mm
  EXPECT_LT(std::abs(b.residual), 0.01);
  EXPECT_LT(std::abs(b.momentum), 1e-9);
}

}  // namespace
}  // namespace ballista::test_otm_contact
