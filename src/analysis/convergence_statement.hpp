#pragma once
// Which level of its deck's grid study a run is, and how far that level is from converged
// (penetration.convergence_record): the study's value of each recorded quantity at the level whose
// band cell is this run's finest cell along the line of flight, against the study's Richardson
// estimate. Only when the run's physics are the study's (deck/physics_fingerprint.hpp): a deck
// whose charge, target or models changed is not the deck the study converged.
#include <string>

#include "io/summary_writer.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Distance from converged within which a level counts as converged (issue's design target: the
/// finest level within 5 % of the Richardson estimate).
inline constexpr double kConvergedWithin = 0.05;

/// Smallest observed order from the three finest levels at which a study's Richardson estimate is
/// trusted (the target: successive differences that shrink at least as fast as h; a lower
/// order extrapolates far beyond the levels it was fitted to).
inline constexpr double kMinimumObservedOrder = 1.0;

/// Whether the study converged the quantity: an estimate, an observed order of at least
/// kMinimumObservedOrder and its finest level within kConvergedWithin of the estimate.
bool converged_in_study(const ConvergenceRecord::Quantity& q);

/// summary.json penetration.convergence: `record`, `study`, `fingerprint_matches`, `level_cell`
/// (m, null when the run's cell is not a level), `quantities` (per name: label, richardson, order,
/// level_value, level_gap = level_value / richardson - 1, run_value from `penetration` at the
/// quantity's summary_key; richardson null when the study found no estimate; `converged_in_study`
/// as converged_in_study() says; level_gap only for a converged quantity run at the level), `within` (the largest
/// |level_gap| of the quantities run at the level, null without a level), `all_converged` and
/// `all_at_level` (every quantity has a value at the level: the study may have run a quantity's
/// finer levels alone, e.g. the casing's hole to 35 us on the plates' band, so a level can be one
/// quantity's and not another's; without that value nothing is known of the other). A run with
/// `patched` grid (grid.patches) is no level: the study refines bands, and a patch changes the
/// cells where the answer is made without changing the band's.
/// A run whose `configuration` fingerprint (deck/physics_fingerprint.hpp: physics and cells) is one
/// of the record's checked configurations, and whose own values of the quantities it recorded are
/// those values (to 1e-6: runs are deterministic; the fingerprint leaves out the end time and the
/// build), is that configuration: `checked` {name, label}, and each
/// quantity's level_value and level_gap are the configuration's (null where it measured none);
/// level_cell stays null. Without a match `checked` is null.
JsonValue convergence_statement(const ConvergenceRecord& record, const std::string& fingerprint,
                                const std::string& configuration, double band_cell, const JsonValue& penetration,
                                bool patched = false);

}  // namespace ballista
