#pragma once
// The fragment figures of one run (tools/plot_fragments.py): fragment_mass_distribution.png (Mott
// plot with the fit), fragment_velocity.png (speed histogram by count and mass) and, with several
// snapshots, fragment_count.png, in the run folder, from its fragments.csv.
#include <string>

namespace ballista {

/// Runs tools/plot_fragments.py OUT_DIR with the BALLISTA_PYTHON interpreter (io/python_tool.hpp).
/// Returns an empty string on success, else what is missing or how the script failed; a failure
/// here is meant as a warning (the run itself is complete).
std::string make_fragment_plots(const std::string& out_dir);

}  // namespace ballista
