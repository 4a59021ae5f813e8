#pragma once
// Which points set the stable time step over a run, sampled every kStepTallyInterval steps.
//
// The summary's min_dt_set_by names the point at the step's lowest; a run's cost is set by what
// holds the step all along. In the perforation demo a handful of jet points on the axis, heated by
// the bulk viscosity and expanded to J ~ 1.7, set three quarters of the steps at about half the
// free jet's Courant step (docs/penetration.md, "What holds the demo's step"). A user reading a slow run
// needs that figure: summary.json statistics.step_set_by, and a headline when a few points hold it.
#include <cstdint>
#include <vector>

#include "core/solver.hpp"
#include "core/state_archive.hpp"
#include "io/summary_writer.hpp"

namespace ballista {

struct Scenario;

/// Steps between two samples of the step's limiter (each sample an O(points) pass, collective on
/// several ranks): 1/64 of the steps costs well under 1 % of a run.
inline constexpr std::int64_t kStepTallyInterval = 64;

/// The distinct particles an entry remembers; beyond that it says "at least".
inline constexpr std::size_t kStepTallyMaxIds = 64;

struct StepTally {
  /// The samples one body set through one kind of signal.
  struct Entry {
    int body = -1;
    bool viscous = false;             ///< the bulk viscosity's signal speed, else the wave speed
    std::int64_t samples = 0;
    std::vector<std::int64_t> ids;    ///< distinct particle ids, sorted, at most kStepTallyMaxIds
    bool ids_capped = false;          ///< more distinct particles than kStepTallyMaxIds
    double J_min = 0.0, J_max = 0.0;  ///< det F of the sampled points
    double signal_max = 0.0;          ///< m/s, the largest signal speed sampled
    double margin_sum = 0.0;          ///< sum of StepLimiter::margin over the samples that have one
    std::int64_t margin_samples = 0;
  };
  std::vector<Entry> entries;  ///< in order of first appearance
  std::int64_t samples = 0;    ///< samples a point set (the entries' sum)
  std::int64_t max_dt_samples = 0;  ///< samples at which simulation.max_dt set the step, no point
  double multirate_sum = 0.0;       ///< sum of StepLimiter::multirate over the samples that have one
  std::int64_t multirate_samples = 0;

  /// Adds one sample (a limiter without a particle is not counted).
  void add(const StepLimiter& l);
  /// summary.json statistics.step_set_by: the sample interval and the entries, most samples first.
  JsonValue json(const Scenario& sc) const;
  void save(StateArchive& a) const;
  /// A checkpoint written before the tally existed leaves it empty.
  void load(const StateArchive& a);
};

}  // namespace ballista
