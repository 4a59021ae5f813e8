#include "run_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "core/console_log.hpp"
#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "io/checkpoint_file.hpp"
#include "io/run_folder.hpp"
#include "run/penetration_plots.hpp"
#include "run/simulation.hpp"

namespace ballista {

namespace {

/// Takes `dir` as the command's results folder on rank 0 (io/run_folder.hpp); the other ranks
/// learn whether it could, so that every rank stops alike when it could not.
void take_folder(std::optional<RunFolder>& folder, const std::string& dir, RunFolder::Mode mode, bool overwrite,
                 const Communicator& world) {
  std::string refused;
  if (world.rank() == 0) try {
      folder.emplace(dir, mode, overwrite);
    } catch (const std::exception& e) {
      refused = e.what();
    }
  if (world.distributed()) refused = world.broadcast(refused, 0);
  if (!refused.empty()) throw CollectiveError(refused);
}

/// What a run starts from: its scenario, its results folder and the checkpoint it continues.
struct RunStart {
  Scenario sc;
  std::string out_dir;
  std::string restart_from;  ///< "" for a new run
};

/// The scenario and results folder of the run: with --restart the checkpoint's deck in its own
/// folder, else the deck given in -o or out/<deck name>; the folder is taken either way.
RunStart start_run(const RunCliOptions& o, std::optional<RunFolder>& folder, const Communicator& world) {
  if (o.deck.empty() && o.restart_dir.empty()) throw Error("run: give a deck, or --restart DIR");
  if (!o.restart_dir.empty() && !o.out_dir.empty() &&
      std::filesystem::path(o.out_dir).lexically_normal() != std::filesystem::path(o.restart_dir).lexically_normal())
    throw Error("run: --restart continues in its own results folder; do not give -o");
  RunStart s;
  s.out_dir = o.out_dir;
  if (!o.restart_dir.empty()) {
    take_folder(folder, o.restart_dir, RunFolder::Mode::Continue, o.overwrite, world);
    // The deck is the one the checkpoint was written with (its resolved text); --set still
    // applies, e.g. a later simulation.end_time.
    const auto [path, deck_text] = newest_checkpoint(o.restart_dir);
    s.restart_from = path;
    s.sc = parse_deck(deck_text, (std::filesystem::path(o.restart_dir) / "resolved.yaml").string(), o.overrides);
    s.out_dir = o.restart_dir;
    if (!o.quiet) std::cerr << "restarting from " << path << "\n";
  } else {
    s.sc = read_deck(o.deck, o.overrides);
    if (s.out_dir.empty()) s.out_dir = "out/" + std::filesystem::path(o.deck).stem().string();
    take_folder(folder, s.out_dir, RunFolder::Mode::NewRun, o.overwrite, world);
  }
  return s;
}

/// --track-failed: runs the deck again from the start with the failed particle tracked, so that
/// its F-table can be replayed with `ballista drive`; `r` and `sc` become the re-run's.
void rerun_tracking_failed(const RunCliOptions& o, const RunOptions& opt, std::optional<RunFolder>& folder,
                           Scenario& sc, RunResult& r) {
  const auto& tracked = sc.output.track;
  if (r.ok || !o.track_failed || !o.restart_dir.empty() || r.failed_particle < 0 ||
      std::find(tracked.begin(), tracked.end(), r.failed_particle) != tracked.end())
    return;
  // Same deck, same thread count, so the run is bitwise the same up to the failure (docs/deck.md,
  // output.track).
  std::string ids;
  for (auto id : tracked) ids += std::to_string(id) + ",";
  ids += std::to_string(r.failed_particle);
  const long first_step = r.failed_step;
  const auto first_particle = r.failed_particle;
  std::cerr << "re-running with output.track.ids = [" << ids << "] to record the history of particle "
            << first_particle << "\n";
  std::vector<std::string> overrides = o.overrides;
  overrides.push_back("output.track.ids=[" + ids + "]");
  sc = read_deck(o.deck, overrides);
  if (folder) folder->clear();
  r = run_simulation(sc, opt);
  if (r.ok || r.failed_particle != first_particle || r.failed_step != first_step)
    std::cerr << "warning: the re-run did not fail the same way (particle " << r.failed_particle << " at step "
              << r.failed_step << ", first run: particle " << first_particle << " at step " << first_step
              << "): the run is not reproducible (different thread count?)\n";
  else
    std::cerr << "history of particle " << first_particle << " up to the failure: "
              << (std::filesystem::path(opt.out_dir) / "tracks" /
                  ("particle_" + std::to_string(first_particle) + ".csv"))
                     .string()
              << " (replay: ballista drive with drive: {table: <that file>, substeps: 1})\n";
}

/// The run's summary on standard output (where to restart, steps, its headline numbers, probes,
/// where the results are) and, for a penetration deck, its figures. With -q: nothing but the
/// figures, and a run that did not complete says so on standard error.
void report_run(const RunResult& r, const Scenario& sc, const std::string& out_dir, const RunCliOptions& o,
                const Communicator& world) {
  // Figures of the penetration run (thesis seed 000 Figs. 7.4-7.7), also after a failure: what
  // ran is worth seeing. A missing Python is a warning, not a failed run.
  bool figures = false;
  if (sc.penetration.enabled && !o.no_plots && world.rank() == 0) {
    const std::string err = make_penetration_plots(out_dir);
    figures = err.empty();
    if (!figures) std::cerr << "warning: no penetration figures: " << err << " (--no-plots skips them)\n";
  }
  if (o.quiet) {
    if (!r.ok && world.rank() == 0)
      std::cerr << (r.interrupted ? "INTERRUPTED" : "FAILED") << " at step " << r.steps << ", t = " << r.time
                << " s" << (r.checkpoint.empty() ? "" : " (ballista run --restart " + out_dir + ")") << "\n";
    return;
  }
  if (!r.checkpoint.empty())
    std::cout << (r.interrupted ? "checkpointed in " : "the last good step is checkpointed in ") << r.checkpoint
              << " (ballista run --restart " << out_dir << ")\n";
  std::cout << (r.ok ? "completed" : r.interrupted ? "INTERRUPTED" : "FAILED") << ": " << r.steps
            << " steps to t = " << r.time << " s in "
            << fmt::format("{:.2f}", r.wall_seconds) << " s (" << fmt::format("{:.3g}", r.particle_steps_per_second)
            << " particle-steps/s)\n";
  for (const auto& line : r.headlines) std::cout << "  " << line << "\n";
  for (const auto& [name, value] : r.probes) std::cout << "  " << name << " = " << value << "\n";
  if (figures)
    std::cout << "  figures: penetration_depth.png, penetration_rate.png, penetrator_energy.png, "
                 "channel_profile.png\n";
  std::cout << "results in " << std::filesystem::absolute(out_dir).string() << "\n";
}

}  // namespace

CLI::App* add_run_command(CLI::App& app, RunCliOptions& o) {
  auto* run = app.add_subcommand("run", "run a deck");
  auto* deck_opt = run->add_option("deck", o.deck, "YAML deck file (not with --restart)")->check(CLI::ExistingFile);
  auto* restart_opt = run->add_option(
      "--restart", o.restart_dir,
      "continue the run whose results folder is DIR from its newest checkpoint (the deck is the checkpoint's; "
      "docs/restart.md)");
  restart_opt->excludes(deck_opt);
  run->add_option("--checkpoint-every-minutes", o.checkpoint_minutes,
                  "also write a checkpoint after every M minutes of wall time (keeps the newest "
                  "output.checkpoint_keep)")
      ->check(CLI::PositiveNumber);
  run->add_option("-o,--output", o.out_dir, "results folder (default out/<deck name>)");
  run->add_option("--threads", o.threads, "OpenMP threads (default: the deck's, else all cores; at most the cores)")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));  // more than the cores is clamped
  run->add_flag("--overwrite", o.overwrite,
                "write into a results folder that is not empty and holds no Ballista run (Ballista then replaces "
                "only the files it writes itself)");
  run->add_option("--set", o.overrides,
                  "override a deck value: key.path=value, or append to a list: key.path+=value (a YAML list "
                  "appends its items); repeatable, applied in order");
  run->add_flag("-q,--quiet", o.quiet,
                "print nothing but errors (warnings are still recorded in summary.json \"warnings\")");
  run->add_flag("--no-plots", o.no_plots,
                "do not draw the figures (PNG): penetration figures of a deck with a penetration section, "
                "fragment figures of a run that writes fragments.csv");
  run->add_flag("--track-failed", o.track_failed,
                "if a particle fails, run the deck again from the start with that particle tracked "
                "(output.track.ids; the run is deterministic for a given thread count), so that its "
                "F-table tracks/particle_<id>.csv can be replayed with `ballista drive`");
  return run;
}

int run_deck_cli(const RunCliOptions& o, const Communicator& world) {
  // Rank 0 holds the results folder for the whole command: the run, its figures and a re-run
  // (io/run_folder.hpp); the other ranks learn whether it could.
  if (o.quiet) quiet_console();  // errors only; warnings still reach summary.json
  std::optional<RunFolder> folder;
  RunStart start = start_run(o, folder, world);
  Scenario& sc = start.sc;
  RunOptions opt;
  opt.folder_held = true;
  opt.restart_from = start.restart_from;
  opt.checkpoint_minutes = o.checkpoint_minutes;
  opt.out_dir = start.out_dir;
  opt.threads = o.threads;
  opt.progress = !o.quiet;
  opt.plots = !o.no_plots;
  RunResult r = run_simulation(sc, opt);
  rerun_tracking_failed(o, opt, folder, sc, r);
  report_run(r, sc, start.out_dir, o, world);
  return r.ok ? 0 : r.interrupted ? 4 : 3;
}

}  // namespace ballista
