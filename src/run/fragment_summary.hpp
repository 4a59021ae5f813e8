#pragma once
// Fragment statistics of a run (docs/validation.md, "Fragment statistics"): when a solver returns a
// result table named "fragments" (fragments.csv: one row per fragment, columns time and mass at
// least, rows grouped by ascending time), summary.json gets "fragments" from its last snapshot,
// with the Mott fit of the masses (analysis/mott_fit.hpp), and the figures are drawn
// (run/fragment_plots.hpp). The run loop reacts to the table's name only; it does not know which
// solver wrote it.
#include <string>
#include <vector>

#include "core/solver.hpp"
#include "io/summary_writer.hpp"

namespace ballista {

/// {time, count, largest_mass, mean_mass, mass_weighted_mean_mass (sum m^2 / sum m), total_mass,
/// mott_N0, mott_mu, mott_r2} of the table's last snapshot (s, -, kg, kg, kg, kg, -, kg, -).
/// Without a Mott fit (fewer than 3 fragments) the mott_* values are left out and mott_reason
/// says why; the means are left out without fragments and mott_r2 when the masses are all equal.
/// With min_mass > 0 (output.fragment_min_mass) also "above_min_mass": {min_mass, and the same
/// statistics over the fragments of at least min_mass}: a lattice's loose points weigh one
/// point's mass each, so they set the mean and the Mott fit of all fragments and halve them with
/// the spacing, where the fragments a test recovers (a sieve, an X-ray) start at a fixed mass.
/// Throws Error if the table has no mass column.
JsonValue fragment_summary(const ResultTable& table, double min_mass = 0.0);

/// The run loop's hook after the result tables are written: if one of `tables` is named
/// "fragments", summary["fragments"] = fragment_summary(it) and, if `plots`, make_fragment_plots
/// in out_dir. Never throws: a failure is logged as a warning (the run itself is complete).
void report_fragments(const std::vector<ResultTable>& tables, const std::string& out_dir, bool plots,
                      JsonValue& summary, double min_mass = 0.0);

}  // namespace ballista
