#pragma once
// Every warning a run logs, kept for its summary.json ("warnings"): a warning says something about
// the results (an under-resolved penetrator, points that left the grid, a probe with nothing to
// measure), so it belongs with them and not only in a console the user may not have kept, or
// silenced with -q.
#include <cstddef>
#include <string>
#include <vector>

namespace ballista {

/// Adds the recording sink to spdlog's default logger (once; later calls do nothing). The sink
/// keeps the text of every message at level warning, whatever the logger's level.
void record_warnings();

/// How many warnings have been recorded so far in this process (a mark for warnings_since).
std::size_t warning_count();

/// The warnings recorded after `mark`, oldest first.
std::vector<std::string> warnings_since(std::size_t mark);

}  // namespace ballista
