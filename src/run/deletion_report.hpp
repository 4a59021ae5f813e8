#pragma once
// Points deleted during a run (simulation.on_particle_exit: delete) are reported as they go, per
// body, with the mass and energy they carry off: a ball that lost 226 of its 228 particles must
// not print its velocity from the last two as if nothing happened. The log says so at the
// history rows where deletions happened, summary.json lists them per body, and a probe whose body
// has lost most of its mass is warned about.
#include <string>
#include <vector>

#include "core/solver.hpp"
#include "io/summary_writer.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class DeletionReport {
 public:
  /// Deletions already booked in `start` (a restart's checkpoint) are not reported again.
  DeletionReport(const Scenario& sc, const EnergyTotals& start);
  /// Logs the deletions since the last call: a body's first, then whenever its deleted share of
  /// its mass crosses another 10 % (debris trickling out of the grid would fill the log).
  void update(const EnergyTotals& e, long step, double time);
  /// summary.json `deleted`: per body that lost points, their count, mass, energy and mass share.
  JsonValue summary(const EnergyTotals& e) const;
  /// One warning per probe whose body has lost more than half its mass (logged by the caller).
  std::vector<std::string> probe_warnings(const EnergyTotals& e) const;


 private:
  const Scenario& sc_;
  std::vector<double> reported_;  ///< points reported so far, per body
  std::vector<int> rows_;         ///< log lines written, per body
  std::vector<int> decile_;       ///< deleted mass share reported, in tenths, per body
};

}  // namespace ballista
