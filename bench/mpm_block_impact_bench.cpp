// Throughput of the MPM solver: a 3D J2 steel block striking a rigid wall at 200 m/s (MUSL, the
// default update; plain USL with linear shape functions inverts surface particles here within
// ~100 steps, the cell-crossing instability).
// Reports particle-steps per second for 1e5 and 1e6 particles, linear and GIMP shape functions,
// on 1 and 2 threads, and for 1e4 and 1e7 particles (linear, 2 threads: the scaling in size; 1e4 also
// on 1 thread);
// GIMP with mpm.update usavg (its second material update, mapping and gradient pass per step),
// and with the artificial bulk viscosity on top (mpm.bulk_viscosity_*: its pass per stress update).
// Setup is not timed.
//   ./build/bench/mpm_block_impact_bench [--benchmark_filter=...]
// Figures and the exact command are recorded in docs/performance.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "block_impact_deck.hpp"
#include "core/parallel.hpp"
#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"

namespace {

std::string deck(long particles, const std::string& shape, double box_volume_ratio = 0.0,
                 const std::string& update = "musl") {
  return ballista::bench::block_impact_deck(particles, shape, box_volume_ratio, update);
}

void BM_BlockImpact(benchmark::State& state, std::string shape, std::string update = "musl",
                    std::vector<std::string> overrides = {}) {
  const long target = state.range(0);
  const int threads = static_cast<int>(state.range(1));
  ballista::set_threads(threads);
  const ballista::Scenario sc = ballista::parse_deck(deck(target, shape, 0.0, update), "bench.yaml", overrides);
  auto solver = ballista::make_solver(sc);
  const double n = static_cast<double>(solver->points().size());
  // Warm-up steps: first touch of the grid and the first sort are not steady state.
  for (int k = 0; k < 3; ++k) solver->step(solver->stable_dt());
  double steps = 0;
  for (auto _ : state) {
    solver->step(solver->stable_dt());
    steps += 1;
  }
  state.counters["particles"] = n;
  state.counters["threads"] = threads;
  state.counters["particle_steps_per_second"] =
      benchmark::Counter(n * steps, benchmark::Counter::kIsRate);
  state.counters["seconds_per_particle_step"] =
      benchmark::Counter(n * steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The same block (1e5 particles, linear, 2 threads) in its tight box (4 empty cells around it) and
// in boxes of 10 and 100 times its volume: the grid work that empty space costs.
void BM_EmptyBox(benchmark::State& state) {
  const double ratio = static_cast<double>(state.range(0));
  ballista::set_threads(2);
  const ballista::Scenario sc = ballista::parse_deck(deck(100000, "linear", ratio > 1 ? ratio : 0.0), "bench.yaml");
  auto solver = ballista::make_solver(sc);
  const double n = static_cast<double>(solver->points().size());
  for (int k = 0; k < 3; ++k) solver->step(solver->stable_dt());
  double steps = 0;
  for (auto _ : state) {
    solver->step(solver->stable_dt());
    steps += 1;
  }
  const ballista::GridSpec& g = sc.grid;
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) cells *= std::round((g.upper[a] - g.lower[a]) / g.cell_size);
  state.counters["particles"] = n;
  state.counters["grid_cells"] = cells;
  state.counters["particle_steps_per_second"] = benchmark::Counter(n * steps, benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_EmptyBox)->Arg(1)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_CAPTURE(BM_BlockImpact, linear, std::string("linear"))
    ->ArgsProduct({{100000, 1000000}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
// The cost per particle-step across sizes (flat from 1e4 to 1e7): linear, 2 threads; and 1e4 on
// one thread, whose cost per particle-step is the 1e5 one-thread figure (what two threads lose).
BENCHMARK_CAPTURE(BM_BlockImpact, scaling_linear, std::string("linear"))
    ->ArgsProduct({{10000, 10000000}, {2}})->Args({10000, 1})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_CAPTURE(BM_BlockImpact, gimp, std::string("gimp"))
    ->ArgsProduct({{100000, 1000000}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_CAPTURE(BM_BlockImpact, gimp_usavg, std::string("gimp"), std::string("usavg"))
    ->ArgsProduct({{100000, 1000000}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_CAPTURE(BM_BlockImpact, gimp_usavg_bulk_viscosity, std::string("gimp"), std::string("usavg"),
                  std::vector<std::string>{"mpm.bulk_viscosity_linear=0.2", "mpm.bulk_viscosity_quadratic=2"})
    ->ArgsProduct({{1000000}, {2}})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

BENCHMARK_MAIN();
