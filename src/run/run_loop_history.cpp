// The run loop's history rows (history.csv), its guards on them (energy drift, non-finite
// values), the deck's probes and the tracked particles.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "analysis/penetration_probe.hpp"
#include "core/energy_terms.hpp"
#include "core/error.hpp"
#include "points/point_exchange.hpp"
#include "run/run_loop.hpp"

namespace ballista {

double RunLoop::energy_scale_of(const EnergyTotals& e) {
  return std::abs(e.kinetic) + std::abs(e.internal) + std::abs(e.external) + std::abs(e.damping) +
         std::abs(e.chemical);
}

std::vector<double> RunLoop::probe_values(const EnergyTotals& e) const {
  const ProbeContext ctx{solver_->points(), e, sc_.simulation.dimension, comm_};
  std::vector<double> v;
  for (const auto& probe : probes_) v.push_back(probe->value(ctx));
  return v;
}

/// Energy drift relative to the largest energy scale seen so far, so that problems that start at
/// rest and are loaded later are measured sensibly.
double RunLoop::drift_of(const EnergyTotals& e) {
  rs_.energy_scale = std::max(rs_.energy_scale, energy_scale_of(e));
  return rs_.energy_scale > 0 ? std::abs(e.total() - rs_.total0) / rs_.energy_scale : 0.0;
}

/// Writes a history row (rank 0) and returns the drift; notes the first non-finite column.
double RunLoop::history_row(double dt) {
  const EnergyTotals e = solver_->energies();
  deletions_->update(e, solver_->steps(), solver_->time());
  const double drift = drift_of(e);
  std::vector<double> row = {solver_->time(), static_cast<double>(solver_->steps()), dt};
  for (const EnergyTerm& t : kEnergyTerms) row.push_back(t.value(e, drift));
  for (double v : probe_values(e)) row.push_back(v);
  if (nstages_ > 0) row.push_back(rs_.stage);
  for (double v : solver_->history_values()) row.push_back(v);
  if (penetration_) {
    // Several ranks: the analysis runs on rank 0 over every rank's particles (gathered), which
    // alone keeps the series and writes the row.
    const FieldStore all = comm_.distributed() ? gather_points(comm_, solver_->points()) : FieldStore{};
    // Every segment in: no point of the run waits for its activation (end_when_spent only).
    const bool all_entered =
        sc_.penetration.end_when_spent > 0.0 && comm_.sum(static_cast<std::int64_t>(solver_->pending_points())) == 0;
    if (root_)
      for (double v : penetration_->sample(comm_.distributed() ? all : solver_->points(), rs_.stage == nstages_,
                                           solver_->time() - rs_.stage_start, solver_->reporting_scale(), all_entered))
        row.push_back(v);
  }
  if (history_) history_->row(row);
  // The first column that overflowed or is not a number (this rank's row: rank 0 alone has the
  // penetration columns); record_history stops the run on it.
  nonfinite_column_.clear();
  for (size_t k = 0; k < row.size() && nonfinite_column_.empty(); ++k)
    if (std::isinf(row[k]) || (std::isnan(row[k]) && !(k < nan_allowed_.size() && nan_allowed_[k])))
      nonfinite_column_ =
          fmt::format("'{}' = {}", k < columns_.size() ? columns_[k] : fmt::format("column {}", k + 1), row[k]);
  return drift;
}

/// A history row, the worst drift so far and the guards: simulation.energy_drift_limit, and any
/// value that overflowed.
void RunLoop::record_history(double step_dt) {
  const double drift = history_row(step_dt);
  tension_.scan(solver_->points(), solver_->time(), comm_);
  rs_.worst_drift = std::max(rs_.worst_drift, drift);
  if (sc_.simulation.energy_drift_limit > 0 && drift > sc_.simulation.energy_drift_limit)
    throw PhysicsError(fmt::format("energy drift {:.6g} exceeds the limit {:.6g} at step {} (t = {:.6g} s): the "
                                   "run is blowing up",
                                   drift, sc_.simulation.energy_drift_limit, solver_->steps(), solver_->time()));
  // A value that overflowed is garbage even when the energies still balance (a probe of a body
  // whose mass overflows, say): the run stops on it instead of ending "ok" with inf in its tables.
  if (comm_.any(!nonfinite_column_.empty()))
    throw PhysicsError(fmt::format("non-finite value in history.csv at step {} (t = {:.6g} s): {}; a probe that "
                                   "selects no particle, or a value that overflowed (check the deck's magnitudes: "
                                   "densities, velocities, moduli)",
                                   solver_->steps(), solver_->time(),
                                   nonfinite_column_.empty() ? "on rank 0" : nonfinite_column_));
}

/// The tracked particles as the tracker sees them: several ranks send theirs to rank 0, which
/// alone records (collective; every rank calls it).
void RunLoop::record_tracks(bool failure) {
  if (tracker_->empty()) return;
  if (!comm_.distributed()) {
    failure ? tracker_->record_failure(solver_->points(), solver_->time())
            : tracker_->record(solver_->points(), solver_->time(), solver_->steps());
    return;
  }
  const FieldStore& local = solver_->points();
  const std::int64_t* id = local.ints("id");
  std::vector<Index> mine;
  for (Index p = 0; p < local.size(); ++p)
    if (tracked_ids_.count(id[p])) mine.push_back(p);
  FieldStore sub = local.empty_like();
  sub.append_from(local, mine);
  const FieldStore all = gather_points(comm_, sub);
  if (!root_) return;
  failure ? tracker_->record_failure(all, solver_->time()) : tracker_->record(all, solver_->time(), solver_->steps());
}

}  // namespace ballista
