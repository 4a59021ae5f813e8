#pragma once
// The `sweep` subcommand of the command line (apps/ballista.cpp). Header-only: CLI11 is a
// dependency of the executable, not of the library.
#include <CLI/CLI.hpp>

#include "run/sweep_cli.hpp"

namespace ballista {

inline CLI::App* add_sweep_command(CLI::App& app, SweepCliOptions& o) {
  auto* s = app.add_subcommand("sweep",
                               "parameter study: run DECK for every combination (Cartesian product) of the --vary "
                               "lists, each in DIR/run_<k>/, and collect the summaries into DIR/sweep.csv and "
                               "DIR/sweep.json; exit 3 if a run failed");
  s->add_option("deck", o.deck, "YAML deck file")->required()->check(CLI::ExistingFile);
  s->add_option("--vary", o.vary,
                "key.path=value1,value2,... (repeatable; commas inside [...] or {...} do not split values)")
      ->required()
      ->allow_extra_args(false);  // one value per --vary, so the deck may follow it
  s->add_option("--set", o.set, "override a deck value in every run: key.path=value, or append to a list: key.path+=value "
                  "(repeatable)")
      ->allow_extra_args(false);
  s->add_option("-j,--jobs", o.jobs,
                "runs at a time; with N > 1 each run gets simulation.threads = max(1, cores / N) unless set")
      ->check(CLI::PositiveNumber);
  s->add_option("-o,--output", o.out_dir, "sweep folder (default out/<deck name>_sweep)");
  s->add_flag("-q,--quiet", o.quiet, "no line per run");
  return s;
}

}  // namespace ballista
