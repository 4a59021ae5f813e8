#pragma once
// A fingerprint of the physics a resolved deck describes, so that a grid study's record can tell
// whether a run is one of its levels. It hashes (FNV-1a, 64 bits) the resolved YAML's lines
// except those a grid study changes from level to level or that do not change the physics:
//   - comment and blank lines;
//   - the `grid` section (the levels) and the `output` section (what is written, not computed);
//   - simulation.end_time (a study may stop a level early to read a quantity that is set by then)
//     and simulation.threads;
//   - penetration.axis_radius and stop_tolerance (their defaults follow the cell) and
//     penetration.convergence_record (the record itself);
//   - keys whose value is `none` or `~` (null): a key a newer build adds with such a default does
//     not change what an earlier build ran.
// validation/convergence_record.py computes the same over a level's resolved.yaml
// (tests/validate/check_convergence_record.py checks the two agree).
#include <string>

namespace ballista {

/// 16 lower-case hex digits.
std::string physics_fingerprint(const std::string& resolved_yaml);

/// The same hash with the `grid` section kept: the physics and the cells together, so that a record
/// can name one whole configuration a study checked against its converged estimate (a grid with
/// patches, a step per region) that is no level of the study.
std::string configuration_fingerprint(const std::string& resolved_yaml);

}  // namespace ballista
