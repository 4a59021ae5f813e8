#include "run/fragment_plots.hpp"

#include <filesystem>

#include "io/python_tool.hpp"
#include "io/run_folder.hpp"

namespace ballista {

std::string make_fragment_plots(const std::string& out_dir) {
  for (const char* figure : {"fragment_mass_distribution.png", "fragment_velocity.png", "fragment_count.png"})
    note_output_file((std::filesystem::path(out_dir) / figure).string());
  return run_python_tool("plot_fragments.py", {out_dir}, "the fragment plot");
}

}  // namespace ballista
