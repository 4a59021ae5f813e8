#pragma once
// The penetration figures of one run (tools/plot_penetration.py, thesis seed 000 Figs. 7.4-7.7):
// penetration_depth.png, penetration_rate.png, penetrator_energy.png, channel_profile.png in the
// run folder, from its history.csv, penetration.csv, channel.csv and summary.json.
#include <string>

namespace ballista {

/// Runs tools/plot_penetration.py OUT_DIR with the BALLISTA_PYTHON interpreter
/// (io/python_tool.hpp). Returns an empty string on success, else what is missing or how the script
/// failed; a failure here is meant as a warning (the run itself is complete).
std::string make_penetration_plots(const std::string& out_dir);

}  // namespace ballista
