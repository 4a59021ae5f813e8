// OTM adaptivity verification (seed 003 ch. 5, Fig. 5-1; issue 14 item 7): the copper Taylor bar
// of examples/taylor_bar_otm.yaml at 750 m/s instead of 227 m/s, axisymmetric, 1.6 mm nodal spacing
// (the CI size of examples/taylor_bar_otm_750.yaml). The bar flattens into a thin disc against the
// frictionless wall; the nodes spread radially and crowd axially until the LME problems of the
// points lose their solutions. Checks:
//  - without adaptivity the run stops with a failed LME solve (a ParticleError naming the point)
//    before 37 us, the time of seed Fig. 5-1 — the failure adaptivity exists for;
//  - with `otm.adaptivity: on` it reaches 100 us with no failed solve, having split points and
//    re-generated the nodes;
//  - the mass is unchanged to round-off (splits share it exactly) and the energy balance, with the
//    re-generations' kinetic-energy change booked as transfer work and the wall's as contact work,
//    closes to 2 % of the initial kinetic energy. What stays unbooked is the momentum form's
//    re-lumping of masses as points (and split children) move among the nodes: measured 1.5 % at
//    this size, 0.5 % at 0.8 mm (docs/validation.md); the elastic impact closes
//    to 0.03 % (test_otm_elastic_impact.cpp, issue 14 item 8's 1 %);
//  - the bar has come to rest: kinetic energy below 1 % of the initial (the rebound of a bar whose
//    energy went almost all into plastic work), and plastic work is more than 3/4 of the initial
//    energy (the balance: elastic energy, the wall's and the re-generations' shares are the rest;
//    measured 85 % at this size, 88 % at 0.8 mm, docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "deck/deck_reader.hpp"
#include "otm/otm_solver.hpp"
#include "run/simulation.hpp"

namespace ballista::test_otm_taylor_750 {
namespace {

std::string deck(const std::string& adaptivity, const std::string& x_max = "10.0e-3") {
  return R"(
simulation: {solver: otm, dimension: axisymmetric, end_time: 1.0e-4, cfl: 0.9}
materials:
  copper: {model: j2_plasticity, density: 8930, youngs_modulus: 117.0e9, poisson_ratio: 0.35,
           yield_stress: 400.0e6, hardening_modulus: 100.0e6}
otm: {gamma: 1.8, wall_model: constraint, adaptivity: )" +
         adaptivity + R"(}
grid: {lower: [0, 0], upper: [)" + x_max + R"(, 34.0e-3], cell_size: 1.6e-3, boundary: {x_min: symmetry, y_min: wall}}
bodies:
  - {name: bar, material: copper, shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 3.2e-3, length: 32.4e-3},
     particles_per_cell: 2, velocity: [0, -750.0, 0]}
)";
}

TEST(OtmTaylor750, FailsWithoutAdaptivityBeforeFig51) {
  const Scenario sc = parse_deck(deck("off"), "taylor_750_off.yaml");
  OtmSolver s(sc, make_materials(sc));
  bool failed = false;
  try {
    while (s.time() < 37.0e-6) s.step(s.stable_dt());
  } catch (const ParticleError& e) {
    failed = std::string(e.what()).find("local max-entropy") != std::string::npos;
    std::printf("without adaptivity: stopped at t = %.3g s\n", s.time());
  }
  EXPECT_TRUE(failed);
}

TEST(OtmTaylor750, RunsTo100usWithAdaptivityAndTheBalanceCloses) {
  const Scenario sc = parse_deck(deck("on"), "taylor_750_on.yaml");
  OtmSolver s(sc, make_materials(sc));
  const EnergyTotals e0 = s.energies();
  while (s.time() < 1.0e-4) s.step(std::min(s.stable_dt(), 1.0e-4 - s.time() + 1e-12));
  const EnergyTotals e = s.energies();
  double splits = 0.0, regenerations = 0.0;
  for (const auto& [k, v] : s.result_values()) {
    if (k == "point_splits") splits = v;
    if (k == "node_regenerations") regenerations = v;
  }
  EXPECT_GT(splits, 0.0);
  EXPECT_GT(regenerations, 0.0);
  EXPECT_NEAR(e.mass, e0.mass, 1e-12 * e0.mass);
  const double residual = (e.total() - e0.total()) / e0.kinetic;
  EXPECT_LT(std::abs(residual), 0.02);
  EXPECT_LT(e.kinetic, 0.01 * e0.kinetic);
  EXPECT_GT(e.plastic, 0.75 * e0.kinetic);
  std::printf("750 m/s, 1.6 mm: %g splits, %g re-generations, residual %.4f, plastic %.3f, transfer %.3f, wall %.3f "
              "of the initial kinetic energy\n",
              splits, regenerations, residual, e.plastic / e0.kinetic, e.transfer / e0.kinetic,
              e.contact / e0.kinetic);
}

// The disc spreads past a narrow box's free x_max face (to r ~ 28 mm at this size). A free face is
// no obstacle: points beyond it split as anywhere else, so the run does not depend on where the
// box ends (a defect found on 2026-11-26: splits near any face, free ones included, were kept
// parallel to it, so points outside the box never split radially).
TEST(OtmTaylor750, AFreeFaceDoesNotConstrainTheSplits) {
  auto run = [](const std::string& x_max) {
    const Scenario sc = parse_deck(deck("on", x_max), "taylor_750_box.yaml");
    OtmSolver s(sc, make_materials(sc));
    while (s.time() < 60.0e-6) s.step(s.stable_dt());
    const auto* x = s.points().view<Vec3>("x");
    return std::vector<Vec3>(x, x + s.points().size());
  };
  const std::vector<Vec3> narrow = run("10.0e-3"), wide = run("45.0e-3");
  ASSERT_EQ(narrow.size(), wide.size());
  double r_max = 0.0;
  for (size_t p = 0; p < narrow.size(); ++p) {
    EXPECT_EQ(narrow[p][0], wide[p][0]);
    EXPECT_EQ(narrow[p][1], wide[p][1]);
    r_max = std::max(r_max, wide[p][0]);
  }
  EXPECT_GT(r_max, 10.0e-3);  // the test means something: material did leave the narrow box
}

// Bitwise independence of the thread count with adaptivity on (the support pass, the force and
// Gershgorin gathers run with a dynamic schedule from 256 points, the splits and re-generations
// serially): 1 and 2 threads to 40 us at 1.6 mm (164 points growing past 700, so both the serial
// and the parallel paths run), positions compared bit for bit.
TEST(OtmTaylor750, AdaptiveRunIsBitwiseIndependentOfTheThreadCount) {
  auto run = [](int threads) {
    set_threads(threads);
    const Scenario sc = parse_deck(deck("on", "45.0e-3"), "taylor_750_threads.yaml");
    OtmSolver s(sc, make_materials(sc));
    while (s.time() < 40.0e-6) s.step(s.stable_dt());
    const auto* x = s.points().view<Vec3>("x");
    return std::vector<Vec3>(x, x + s.points().size());
  };
  const int saved = max_threads();
  const std::vector<Vec3> one = run(1), two = run(2);
  set_threads(saved);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_GT(one.size(), 256u);
  for (size_t p = 0; p < one.size(); ++p)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(one[p][c], two[p][c]) << p;
}

}  // namespace
}  // namespace ballista::test_otm_taylor_750
