// Cost of one constitutive update per point through the material adapter (polar decomposition,
// unrotated frame, kernel, energy bookkeeping), the path every solver takes. Reports nanoseconds
// per point update for elastic and plastic J2 steps (default linear hardening, and Voce with
// kinematic hardening), Johnson-Cook plastic steps and the elastic models.
//   ./build/bench/material_update_bench
#include <benchmark/benchmark.h>

#include <random>

#include "core/parallel.hpp"
#include "material_batch_fixture.hpp"
#include "materials/material.hpp"

namespace {

using namespace ballista;

ParamValues elastic() { return {{"density", 8930}, {"youngs_modulus", 117e9}, {"poisson_ratio", 0.35}}; }
/// The Taylor-anvil copper of CATALOGUE B6: the default j2_plasticity configuration (fast path).
ParamValues j2_linear() {
  ParamValues v = elastic();
  v["yield_stress"] = 400e6;
  v["hardening_modulus"] = 100e6;
  return v;
}
/// Voce isotropic + linear kinematic hardening: the general path with the Newton return.
ParamValues j2_voce_kinematic() {
  ParamValues v = elastic();
  v["yield_stress"] = 400e6;
  v.choices["hardening_law"] = "voce";
  v["hardening_modulus"] = 100e6;
  v["saturation_stress"] = 200e6;
  v["saturation_rate"] = 10.0;
  v["kinematic_modulus"] = 1e9;
  return v;
}

void BM_MaterialUpdate(benchmark::State& state, std::string model, ParamValues v, double strain_rate) {
  set_threads(1);
  const Index n = 100000;
  // johnson_cook: the OFHC copper example (Mie-Grüneisen EOS, heating, rate term).
  if (model == "johnson_cook") v = find_material(model)->example();
  auto mat = find_material(model)->create("m", v);
  bench::MaterialBatchFixture fx(*mat, n);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  const double dt = 1e-8;
  for (Index p = 0; p < n; ++p) {
    Mat3 L;
    for (double& a : L.a) a = strain_rate * u(rng);
    fx.L()[p] = L;
    fx.F()[p] = Mat3::identity() + dt * L;
  }
  const MaterialBatch b = fx.batch(dt);
  for (auto _ : state) mat->update(b);
  // items_per_second = point updates per second; ns per point update = 1e9 / items_per_second.
  state.SetItemsProcessed(static_cast<std::int64_t>(n) * state.iterations());
}

}  // namespace

// 1e3 1/s keeps J2 elastic over the benchmark; 1e7 1/s yields on the first steps. Johnson-Cook at
// 1e6 1/s (1 % strain per step, every step plastic; heats ~1 K per iteration, far from melting over
// a benchmark run).
BENCHMARK_CAPTURE(BM_MaterialUpdate, j2_elastic_steps, std::string("j2_plasticity"), j2_linear(), 1e3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MaterialUpdate, j2_plastic_steps, std::string("j2_plasticity"), j2_linear(), 1e7)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MaterialUpdate, j2_voce_kinematic_elastic_steps, std::string("j2_plasticity"),
                  j2_voce_kinematic(), 1e3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MaterialUpdate, j2_voce_kinematic_plastic_steps, std::string("j2_plasticity"),
                  j2_voce_kinematic(), 1e7)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MaterialUpdate, johnson_cook_plastic_steps, std::string("johnson_cook"), ParamValues{}, 1e6)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MaterialUpdate, linear_elastic, std::string("linear_elastic"), elastic(), 1e3)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MaterialUpdate, neo_hookean, std::string("neo_hookean"), elastic(), 1e3)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
