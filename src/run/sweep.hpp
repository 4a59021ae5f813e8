#pragma once
// `ballista sweep` (docs/sweep.md): a parameter study over the Cartesian product of --vary lists.
// Every combination's deck is read and validated up front (nothing runs if one is bad); then each
// run is a child process `ballista run DECK -o DIR/run_<k> --set ...` of the same executable, at
// most `jobs` at a time, so a crash or a failed run cannot take the sweep down. Their summary.json
// files are collected into DIR/sweep.csv and DIR/sweep.json (run/sweep_table.hpp).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "run/sweep_table.hpp"

namespace ballista {

/// An analysis of the finished table, run after sweep.csv/json are written, given the table and
/// the sweep folder (e.g., later, the U = a + bV fit and U-V plots of an impact-velocity sweep).
using SweepPostStep = std::function<void(const SweepTable& table, const std::filesystem::path& out_dir)>;

struct SweepOptions {
  std::string deck;               ///< the base deck
  std::vector<std::string> vary;  ///< "key.path=v1,v2,..." (one axis each)
  std::vector<std::string> set;   ///< "key.path=value" applied to every run (before the varied values)
  std::filesystem::path out_dir;  ///< sweep folder: run_<k>/, sweep.csv, sweep.json
  int jobs = 1;                   ///< runs at a time
  int cores = 0;                  ///< cores to share among jobs (0: std::thread::hardware_concurrency)
  bool quiet = false;             ///< no per-run lines on stdout
  std::string executable;         ///< the ballista binary that runs each deck
  std::vector<SweepPostStep> post_steps;
};

/// One run of the plan.
struct SweepRunSpec {
  int index = 0;
  std::vector<std::string> values;     ///< one per axis
  std::vector<std::string> overrides;  ///< all --set overrides of this run, in order
  std::filesystem::path dir;           ///< out_dir/run_<index>
};

struct SweepPlan {
  std::vector<SweepAxis> axes;
  std::vector<SweepRunSpec> runs;
  int threads_per_run = 0;  ///< simulation.threads given to each run (0: left to the deck)
};

/// A deck that does not read for one combination: names the run and its varied values, then the
/// deck error (file, line, key path, what was expected).
class SweepDeckError : public Error {
 public:
  using Error::Error;
};

/// Threads per run with `jobs` concurrent runs on `cores` cores: max(1, cores / jobs).
int sweep_threads_per_run(int cores, int jobs);

/// Parses the options, expands the product and reads every run's deck (without running it).
/// With jobs > 1 each run gets simulation.threads = sweep_threads_per_run unless --set or --vary
/// sets simulation.threads itself. Throws Error for bad options, SweepDeckError for a bad deck.
SweepPlan plan_sweep(const SweepOptions& o);

/// Plans, runs every combination, writes the table and runs the post steps; returns the table
/// (table.failed() runs did not complete). Throws like plan_sweep before anything runs.
SweepTable run_sweep(const SweepOptions& o);

}  // namespace ballista
