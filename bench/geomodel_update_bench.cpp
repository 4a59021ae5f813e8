// Cost of one geomodel point update through the material adapter (the path every solver takes),
// in nanoseconds per point update, for the Berea presets of data/materials.yaml:
//   elastic steps       - confined at a mean stress of -50 MPa (inside the surface), small random
//                         strain increments whose sign alternates between iterations;
//   shear plastic steps - confined, then sheared at a high rate: every step returns to the limit
//                         surface;
//   compaction steps    - hydrostatic compression past the cap: every step crushes pores and moves
//                         the cap (consistency iteration), with pore fluid in the saturated set;
//   confined shear      - confined at 5 ksi (the perforation demo's rock), sheared at 1e4 1/s in a
//                         fixed deviatoric direction per point: every step is a hardening return.
//                         The strain is prescribed, so the dilatancy, held at a fixed volume,
//                         compresses the point towards the cap, and the returns are mostly the
//                         cap's (under prescribed confining stress the same shear stays on the
//                         limit surface). The demo's yielding rock has both: 40 % of its intact
//                         points plastic in a step at 60 us, I1 from -0.76 to -0.06 GPa. Each
//                         timed block of 10 steps starts from the same state, reached by 40
//                         untimed steps and restored untimed.
//   ./build/bench/geomodel_update_bench
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "deck/material_presets.hpp"
#include "material_batch_fixture.hpp"
#include "materials/material.hpp"

namespace {

using namespace ballista;

enum class Load { Elastic, Shear, Compaction, ConfinedShear };

ParamValues preset(const std::string& name) {
  static const MaterialPresetLibrary lib = MaterialPresetLibrary::load_default();
  return preset_param_values(lib.get(name), find_material("geomodel")->params);
}

void BM_Geomodel(benchmark::State& state, std::string preset_name, Load load) {
  set_threads(1);
  const Index n = 20000;
  auto mat = find_material("geomodel")->create("rock", preset(preset_name));
  bench::MaterialBatchFixture fx(*mat, n);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  const double dt = 1e-7;
  // Strain rates: 1e2 1/s keeps every step elastic (1e-5 strain per step, alternating sign);
  // 1e5 1/s shears 1 % per step, the confined shear 0.1 %; compaction 2e3 1/s volumetric (2e-4
  // per step).
  const double rate = load == Load::Elastic         ? 1e2
                      : load == Load::Shear         ? 1e5
                      : load == Load::ConfinedShear ? 1e4
                                                    : 2e3;
  // Start confined at a mean stress of -50 MPa (compaction: at the cap, I1 = P0, so every step is
  // plastic from the first; the confined shear: at the demo's 5 ksi, -34.48 MPa).
  const double mean = load == Load::Compaction      ? -1.14e9 / 3.0
                      : load == Load::ConfinedShear ? -34.48e6
                                                    : -50e6;
  for (Index p = 0; p < n; ++p) {
    Mat3 L;
    if (load == Load::Compaction) {
      L = (-rate / 3.0) * Mat3::identity();
      for (double& a : L.a) a += 0.01 * rate * u(rng);
    } else {
      for (double& a : L.a) a = rate * u(rng);
      if (load == Load::ConfinedShear) L = L - (trace(L) / 3.0) * Mat3::identity();  // deviatoric
    }
    fx.L()[p] = L;
    fx.F()[p] = Mat3::identity() + dt * L;
    fx.stress()[p] = mean * Mat3::identity();
  }
  const MaterialBatch b = fx.batch(dt);
  FieldStore& s = fx.store;
  Mat3* L = s.view<Mat3>("L");
  double plastic = 0.0;
  // ConfinedShear: sheared untimed until it yields, then every block of kBlock steps restarts there.
  constexpr int kBlock = 10;
  std::vector<std::string> kept{"stress", "R"};
  for (const auto& f : mat->state_fields()) kept.push_back(f.name);
  std::vector<std::vector<double>> snapshot;
  if (load == Load::ConfinedShear) {
    for (int k = 0; k < 40; ++k) mat->update(b);
    for (const auto& name : kept) {
      const double* d = s.real(name);
      snapshot.emplace_back(d, d + n * s.info(name).ncomp);
    }
  }
  int step = 0;
  for (auto _ : state) {
    if (load == Load::ConfinedShear && step++ % kBlock == 0) {
      state.PauseTiming();
      for (std::size_t f = 0; f < kept.size(); ++f) std::copy(snapshot[f].begin(), snapshot[f].end(), s.real(kept[f]));
      state.ResumeTiming();
    }
    mat->update(b);
    if (load == Load::Elastic)
      for (Index p = 0; p < n; ++p) L[p] *= -1.0;  // back and forth: stays elastic
  }
  for (Index p = 0; p < n; ++p) plastic += s.real("eqps")[p] + std::abs(s.real("plastic_volumetric_strain")[p]);
  // items_per_second = point updates per second; ns per point update = 1e9 / items_per_second.
  state.SetItemsProcessed(static_cast<std::int64_t>(n) * state.iterations());
  state.counters["mean_plastic_strain"] = plastic / n;
  state.counters["mean_substeps"] = [&] {
    double m = 0;
    for (Index p = 0; p < n; ++p) m += s.real("substeps")[p];
    return m / n;
  }();
}

}  // namespace

BENCHMARK_CAPTURE(BM_Geomodel, drained_elastic_steps, std::string("sandstone_berea_drained"), Load::Elastic)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Geomodel, drained_shear_plastic_steps, std::string("sandstone_berea_drained"), Load::Shear)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Geomodel, drained_compaction_steps, std::string("sandstone_berea_drained"), Load::Compaction)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Geomodel, drained_confined_shear_steps, std::string("sandstone_berea_drained"),
                  Load::ConfinedShear)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Geomodel, saturated_elastic_steps, std::string("sandstone_berea_saturated"), Load::Elastic)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Geomodel, saturated_shear_plastic_steps, std::string("sandstone_berea_saturated"), Load::Shear)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Geomodel, saturated_compaction_steps, std::string("sandstone_berea_saturated"),
                  Load::Compaction)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
