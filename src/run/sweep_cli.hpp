#pragma once
// `ballista sweep` behind the command line (apps/ballista.cpp, run/sweep_command.hpp).
#include <string>
#include <vector>

namespace ballista {

struct SweepCliOptions {
  std::string deck;
  std::vector<std::string> vary;  ///< --vary key.path=v1,v2,... (repeatable; Cartesian product)
  std::vector<std::string> set;   ///< --set key.path=value (every run)
  std::string out_dir;            ///< -o (default out/<deck name>_sweep)
  int jobs = 1;                   ///< --jobs
  bool quiet = false;
};

/// Runs the sweep with this executable (`argv0`, resolved through /proc/self/exe when possible)
/// and prints a summary. Returns 0 if every run completed, 3 if some failed, 2 for a deck error of
/// some combination (nothing runs), 1 for a bad option.
int run_sweep_cli(const SweepCliOptions& o, const std::string& argv0);

}  // namespace ballista
