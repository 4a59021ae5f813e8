// Throughput of the OTM solver (issue 14 item 9): the copper Taylor bar of
// examples/taylor_bar_otm.yaml (axisymmetric, 227 m/s, gamma 1.8, 2 x 2 points per cell, CFL 0.9
// of the Gershgorin step) at three nodal spacings, 0.8, 0.4 and 0.2 mm (648, 2,592 and 10,368
// points), and the 3D quarter bar at 0.8 mm (4,212 points). Each case first runs untimed to
// t = 10 us, so the foot has formed and the supports have their deformed sizes (the cost per
// point-step grows with the support size), then times `steps` steps. Reports point-steps per
// second and the split of the step into its phases (supports: cell-binning search and LME
// solves; assemble: lumped masses and forces; node update; point update: positions, F, volumes;
// material: the shared library's stress update; stable_dt: the Gershgorin bound; Solver::timing_values).
//   ./build/bench/otm_taylor_bench [--benchmark_filter=...]
// Figures and the exact command are recorded in docs/performance.md ("OTM throughput").
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

#include "core/parallel.hpp"
#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"

namespace {

std::string deck(double h, bool three_d) {
  char buf[2048];
  if (!three_d) {
    std::snprintf(buf, sizeof buf, R"(
simulation: {solver: otm, dimension: axisymmetric, end_time: 1.0e-4, cfl: 0.9}
materials:
  copper: {model: j2_plasticity, density: 8930, youngs_modulus: 117.0e9, poisson_ratio: 0.35,
           yield_stress: 400.0e6, hardening_modulus: 100.0e6}
otm: {gamma: 1.8, wall_model: constraint}
grid: {lower: [0, 0], upper: [10.0e-3, 34.0e-3], cell_size: %g, boundary: {x_min: symmetry, y_min: wall}}
bodies:
  - {name: bar, material: copper, shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 3.2e-3, length: 32.4e-3},
     particles_per_cell: 2, velocity: [0, -227.0, 0]}
)",
                  h);
  } else {
    std::snprintf(buf, sizeof buf, R"(
simulation: {solver: otm, dimension: 3d, end_time: 1.0e-4, cfl: 0.9}
materials:
  copper: {model: j2_plasticity, density: 8930, youngs_modulus: 117.0e9, poisson_ratio: 0.35,
           yield_stress: 400.0e6, hardening_modulus: 100.0e6}
otm: {gamma: 1.8, wall_model: constraint}
grid: {lower: [0, 0, 0], upper: [10.0e-3, 34.0e-3, 10.0e-3], cell_size: %g,
       boundary: {x_min: symmetry, z_min: symmetry, y_min: wall}}
bodies:
  - {name: bar, material: copper, shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 3.2e-3, length: 32.4e-3},
     particles_per_cell: 2, velocity: [0, -227.0, 0]}
)",
                  h);
  }
  return buf;
}

void BM_OtmTaylor(benchmark::State& state, bool three_d) {
  const double h = 1e-6 * static_cast<double>(state.range(0));  // range in micrometres
  const int threads = static_cast<int>(state.range(1));
  ballista::set_threads(threads);
  const ballista::Scenario sc = ballista::parse_deck(deck(h, three_d), "otm_bench.yaml");
  auto solver = ballista::make_solver(sc);
  while (solver->time() < 10.0e-6) solver->step(solver->stable_dt());
  auto phases = [&] {
    std::map<std::string, double> s;
    for (const auto& [k, v] : solver->timing_values()) s[k] = v;
    return s;
  };
  const std::map<std::string, double> before = phases();
  const double n = static_cast<double>(solver->points().size());
  double steps = 0;
  for (auto _ : state) {
    solver->step(solver->stable_dt());
    steps += 1;
  }
  const std::map<std::string, double> after = phases();
  double total = 0.0;
  for (const auto& [k, v] : after) total += v - before.at(k);
  for (const auto& [k, v] : after)
    state.counters["share_" + k] = total > 0.0 ? (v - before.at(k)) / total : 0.0;
  double support_mean = 0.0, nodes = 0.0;
  for (const auto& [k, v] : solver->result_values()) {
    if (k == "support_mean") support_mean = v;
    if (k == "node_count") nodes = v;
  }
  state.counters["points"] = n;
  state.counters["nodes"] = nodes;
  state.counters["support_mean"] = support_mean;
  state.counters["threads"] = threads;
  state.counters["point_steps_per_second"] = benchmark::Counter(n * steps, benchmark::Counter::kIsRate);
}

}  // namespace

// Nodal spacing in micrometres x threads. Axisymmetric: 0.8 / 0.4 / 0.2 mm; 3D quarter bar: 0.8 mm.
BENCHMARK_CAPTURE(BM_OtmTaylor, axisymmetric, false)
    ->ArgsProduct({{800, 400, 200}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_CAPTURE(BM_OtmTaylor, quarter_3d, true)
    ->ArgsProduct({{800}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

BENCHMARK_MAIN();
