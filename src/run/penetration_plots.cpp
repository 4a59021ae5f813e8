#include "run/penetration_plots.hpp"

#include <filesystem>

#include "io/python_tool.hpp"
#include "io/run_folder.hpp"

namespace ballista {

std::string make_penetration_plots(const std::string& out_dir) {
  for (const char* figure : {"penetration_depth.png", "penetration_rate.png", "penetrator_energy.png",
                             "channel_profile.png"})
    note_output_file((std::filesystem::path(out_dir) / figure).string());
  return run_python_tool("plot_penetration.py", {out_dir}, "the penetration plot");
}

}  // namespace ballista
