#include "run/fragment_plots.hpp"

#include "io/python_tool.hpp"

namespace ballista {

std::string make_fragment_plots(const std::string& out_dir) {
  return run_python_tool("plot_fragments.py", {out_dir}, "the fragment plot");
}

}  // namespace ballista
