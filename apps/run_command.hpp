#pragma once
// The `run` subcommand of the command line (apps/ballista.cpp): run a deck, or continue a run from
// its newest checkpoint, in a results folder held for the whole command. In its own file: it is
// the largest subcommand, and the CLI file only adds it and calls run_deck_cli.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/communicator.hpp"

namespace ballista {

/// The options of `ballista run`, as CLI11 fills them.
struct RunCliOptions {
  std::string deck;
  std::string out_dir;      ///< -o; default out/<deck name>, or the --restart folder
  std::string restart_dir;  ///< --restart: the results folder to continue
  int threads = 0;
  std::vector<std::string> overrides;  ///< --set key.path=value
  bool quiet = false;
  double checkpoint_minutes = 0.0;
  bool overwrite = false;
  bool no_plots = false;
  bool track_failed = false;
};

/// Adds the `run` subcommand to `app`, its options filling `o`.
CLI::App* add_run_command(CLI::App& app, RunCliOptions& o);

/// Runs `ballista run` on every rank of `world` and returns its exit code (0 done, 3 failed,
/// 4 interrupted); deck and other errors are thrown for main to report.
int run_deck_cli(const RunCliOptions& o, const Communicator& world);

}  // namespace ballista
