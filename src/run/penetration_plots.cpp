#include "run/penetration_plots.hpp"

#include "io/python_tool.hpp"

namespace ballista {

std::string make_penetration_plots(const std::string& out_dir) {
  return run_python_tool("plot_penetration.py", {out_dir}, "the penetration plot");
}

}  // namespace ballista
