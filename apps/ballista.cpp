// The `ballista` command line: run a deck, drive a single material point, list what is registered.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "core/communicator.hpp"
#include "core/error.hpp"
#include "core/threads.hpp"
#include "driver/drive_run.hpp"
#include "io/checkpoint_file.hpp"
#include "io/deck_reader.hpp"
#include "io/run_folder.hpp"
#include "io/material_presets.hpp"
#include "materials/material.hpp"
#include "mpm/shape_functions.hpp"
#include "points/initial_state_registry.hpp"
#include "points/load_registry.hpp"
#include "points/probe_registry.hpp"
#include "points/solver_registry.hpp"
#include "penetration/models_command.hpp"
#include "run/penetration_plots.hpp"
#include "run/simulation.hpp"
#include "run/sweep_command.hpp"
#include "verify/verify_command.hpp"

namespace {

std::string format_default(const ballista::ParamSpec& p) {
  if (!p.choices.empty()) {
    std::string opts;
    for (const auto& c : p.choices) opts += (opts.empty() ? "" : " | ") + c;
    return opts + "; default " + p.default_choice;
  }
  if (p.required) return "required";
  if (std::isnan(p.default_value)) return "optional";
  return fmt::format("default {:g}", p.default_value);
}

std::string format_range(const ballista::ParamSpec& p) {
  std::string lo = std::isinf(p.min) ? "" : fmt::format("{:g} {} ", p.min, p.min_exclusive ? "<" : "<=");
  std::string hi = std::isinf(p.max) ? "" : fmt::format(" {} {:g}", p.max_exclusive ? "<" : "<=", p.max);
  if (lo.empty() && hi.empty()) return "";
  return lo + "x" + hi;
}

/// One line of `ballista info` for a probe parameter: key, unit, description, default, range.
std::string format_probe_param(const ballista::ProbeParam& p) {
  using Kind = ballista::ProbeParam::Kind;
  std::string what = p.description;
  if (p.kind == Kind::Axis) what += "; x | y | z (x | y in 2D)";
  if (p.kind == Kind::Word && !p.choices.empty()) {
    std::string words;
    for (const auto& c : p.choices) words += (words.empty() ? "" : " | ") + c;
    what += "; " + words;
  }
  if (p.kind == Kind::Number || p.kind == Kind::Vector)
    what += p.required ? "; required" : fmt::format("; default {:g}", p.default_value);
  if (p.kind == Kind::Number && !std::isinf(p.min))
    what += fmt::format("; range {:g} {} x", p.min, p.min_exclusive ? "<" : "<=");
  return fmt::format("      {:<30} [{}] {}\n", p.name, p.unit.empty() ? "-" : p.unit, what);
}

/// Names joined as in prose ("a", "a and b", "a, b and c"): lists of solvers drawn from the registry.
std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (size_t k = 0; k < names.size(); ++k)
    s += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  return s;
}

/// The program's one-line description, naming the registered solvers (a new one needs no edit here).
std::string app_description() {
  std::vector<std::string> names;
  for (const auto& f : ballista::solver_registry()) names.push_back(f.name);
  return "Ballista: solids under extreme deformation (" + join_names(names) + ")";
}

void print_info() {
  std::cout << "Ballista " << BALLISTA_VERSION << "\n\nSolvers (simulation.solver; parameters in the section named)\n";
  for (const auto& f : ballista::solver_registry()) {
    std::string dims;
    for (const auto& d : f.dimensions) dims += (dims.empty() ? "" : ", ") + d;
    std::cout << "  " << f.name << "  " << f.description << "; dimensions " << dims << "\n";
    for (const auto& p : f.params)
      std::cout << fmt::format("      {:<30} [{}] {}; {}{}\n", f.section + "." + p.name, p.unit, p.description,
                               format_default(p), format_range(p).empty() ? "" : "; range " + format_range(p));
  }
  // The solvers that read simulation.cfl, and the section keys that choose a shape function, as
  // the registry has them.
  std::string cfl_solvers, shape_keys;
  for (const auto& f : ballista::solver_registry()) {
    if (f.courant_step) cfl_solvers += (cfl_solvers.empty() ? "" : ", ") + f.name;
    for (const auto& p : f.params)
      if (p.name == "shape_function") shape_keys += (shape_keys.empty() ? "" : ", ") + f.section + "." + p.name;
  }
  std::cout << "  (" << cfl_solvers
            << ") simulation.cfl [1] Courant number of the stable step; default 0.3; range 0 < x <= 1\n"
               "  (every solver) simulation.damping [1/s] damping a - c v (dynamic relaxation); default 0\n";
  std::cout << "\nShape functions (" << shape_keys << ")\n";
  for (const auto& n : ballista::shape_kind_names())
    std::cout << "  " << n << "  " << ballista::shape_kind_description(ballista::parse_shape_kind(n)) << "\n";
  std::cout << "\nProbes (probes[].type; each probe is a history.csv column and a summary.json value)\n";
  for (const auto& f : ballista::probe_registry()) {
    std::cout << "  " << f.name << "  " << f.description << "\n";
    for (const auto& p : f.params) std::cout << format_probe_param(p);
  }
  std::cout << "\nLoads (loads[].type; their keys in docs/deck.md)\n";
  for (const auto& f : ballista::load_registry()) std::cout << "  " << f.name << "  " << f.description << "\n";
  std::cout << "\nInitial states (bodies[].initial_state; default none)\n";
  for (const auto& f : ballista::initial_state_registry())
    std::cout << "  " << f.name << "  " << f.description << "\n";
  std::cout << "\nMaterials (materials.<name>.model)\n";
  for (const auto& f : ballista::material_registry()) {
    std::cout << "  " << f.model << "  " << f.description << "\n";
    for (const auto& p : f.params)
      std::cout << fmt::format("      {:<30} [{}] {}; {}{}\n", p.name, p.unit, p.description,
                               format_default(p),
                               format_range(p).empty() ? "" : "; range " + format_range(p));
    if (!f.state_fields.empty()) {
      std::cout << "      state fields:";
      for (const auto& s : f.state_fields) std::cout << " " << s.name << " [" << s.unit << "]";
      std::cout << "\n";
    }
    std::cout << "      (a point holds the subset its parameters use; with a failure.criterion also damage [1] and\n"
                 "       failed [1])\n";
  }
  // Cited parameter sets usable as `preset: NAME` in a deck material (docs/material_data.md).
  try {
    const auto lib = ballista::MaterialPresetLibrary::load_default();
    std::cout << "\nMaterial presets (materials.<name>.preset; " << lib.file() << ")\n";
    size_t width = 0;  // the name column fits the longest name
    for (const auto& p : lib.presets()) width = std::max(width, p.name.size());
    for (const auto& p : lib.presets())
      std::cout << fmt::format("  {:<{}} {:<14} {}\n", p.name, width, p.model, p.description);
  } catch (const std::exception& e) {
    std::cout << "\nMaterial presets: not available (" << e.what() << ")\n";
  }
}

/// An error on standard error in one write, so that the lines of several ranks do not interleave
/// ("error: error: ..."); a rank other than 0 names itself.
void report_error(const char* kind, const std::string& what, const ballista::Communicator& world) {
  const std::string line = (world.rank() == 0 ? std::string() : "rank " + std::to_string(world.rank()) + ": ") + kind +
                           ballista::shorten(what, 2500) + "\n";
  std::fwrite(line.data(), 1, line.size(), stderr);
  std::fflush(stderr);
}

}  // namespace

int main(int argc, char** argv) {
  // OpenMP threads sleep instead of spinning while they wait, unless the user chose a policy: may
  // re-execute this program (libgomp reads its environment before main; docs/performance.md).
  ballista::ensure_omp_wait_policy(argv);
  // Launched by mpirun: MPI for the run's ranks (docs/parallel.md); finalised when main returns.
  ballista::Communicator::init_if_launched(&argc, &argv);
  struct MpiFinalize {
    ~MpiFinalize() { ballista::Communicator::finalize(); }
  } mpi_finalize;
  const ballista::Communicator world = ballista::Communicator::world();
  // Rank 0 reports; the other ranks print only errors of their own (std::cout goes to /dev/null
  // until main returns, then gets its own buffer back).
  std::ofstream quiet_rank;
  struct RestoreCout {
    std::streambuf* saved = nullptr;
    ~RestoreCout() {
      if (saved) std::cout.rdbuf(saved);
    }
  } restore_cout;
  if (world.rank() != 0) {
    spdlog::set_level(spdlog::level::err);
    quiet_rank.open("/dev/null");
    restore_cout.saved = std::cout.rdbuf(quiet_rank.rdbuf());
  }
  CLI::App app{app_description()};
  app.set_version_flag("--version", std::string("ballista ") + BALLISTA_VERSION);
  app.require_subcommand(1);

  auto* run = app.add_subcommand("run", "run a deck");
  std::string deck, out_dir;
  int threads = 0;
  std::vector<std::string> overrides;
  bool quiet = false;
  std::string restart_dir;
  double checkpoint_minutes = 0.0;
  auto* deck_opt = run->add_option("deck", deck, "YAML deck file (not with --restart)")->check(CLI::ExistingFile);
  auto* restart_opt = run->add_option(
      "--restart", restart_dir,
      "continue the run whose results folder is DIR from its newest checkpoint (the deck is the checkpoint's; "
      "docs/restart.md)");
  restart_opt->excludes(deck_opt);
  run->add_option("--checkpoint-every-minutes", checkpoint_minutes,
                  "also write a checkpoint after every M minutes of wall time (keeps the newest "
                  "output.checkpoint_keep)")
      ->check(CLI::PositiveNumber);
  run->add_option("-o,--output", out_dir, "results folder (default out/<deck name>)");
  run->add_option("--threads", threads, "OpenMP threads (default: the deck's, else all cores; at most the cores)")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));  // more than the cores is clamped
  bool overwrite = false;
  run->add_flag("--overwrite", overwrite,
                "write into a results folder that is not empty and holds no Ballista run (Ballista then replaces "
                "only the files it writes itself)");
  run->add_option("--set", overrides, "override a deck value: key.path=value (repeatable)");
  run->add_flag("-q,--quiet", quiet, "no progress output");
  bool no_plots = false;
  run->add_flag("--no-plots", no_plots,
                "do not draw the figures (PNG): penetration figures of a deck with a penetration section, "
                "fragment figures of a run that writes fragments.csv");
  bool track_failed = false;
  run->add_flag("--track-failed", track_failed,
                "if a particle fails, run the deck again from the start with that particle tracked "
                "(output.track.ids; the run is deterministic for a given thread count), so that its "
                "F-table tracks/particle_<id>.csv can be replayed with `ballista drive`");

  auto* drive = app.add_subcommand("drive", "drive one material point through an F-table or strain/stress legs");
  std::string drive_deck, drive_out;
  std::vector<std::string> drive_overrides;
  double scale = 1.0, noise = 0.0;
  std::string seed;  // validated as the deck key drive.seed, with its message (one check, one wording)
  bool drive_quiet = false;
  drive->add_option("deck", drive_deck, "YAML drive deck (materials + drive)")->required()->check(CLI::ExistingFile);
  drive->add_option("-o,--output", drive_out, "results folder (default out/<deck name>)");
  drive->add_option("--set", drive_overrides, "override a deck value: key.path=value (repeatable)");
  auto* scale_opt =
      drive->add_option("--scale", scale, "scale the table's deformation: F -> I + S (F - I) (drive.scale)");
  auto* noise_opt = drive->add_option("--noise", noise,
                                      "multiplicative noise of amplitude A on the table's increments (drive.noise)");
  auto* seed_opt = drive->add_option("--seed", seed, "seed of the noise (drive.seed; 0 <= seed < 2^63)");
  seed_opt->needs(noise_opt);
  drive->add_flag("-q,--quiet", drive_quiet, "print nothing on success");

  auto* info = app.add_subcommand("info", "list registered solvers, shape functions and materials");
  ballista::VerifyCliOptions verify_opt;
  auto* verify = ballista::add_verify_command(app, verify_opt);
  ballista::penetration::ModelsCliOptions models_opt;
  auto* models = ballista::add_models_command(app, models_opt);
  ballista::SweepCliOptions sweep_opt;
  auto* sweep = ballista::add_sweep_command(app, sweep_opt);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*verify) return ballista::run_verify_cli(verify_opt);
    if (*models) return ballista::penetration::run_models_cli(models_opt);
    if (*sweep) return ballista::run_sweep_cli(sweep_opt, argv[0]);
    if (*info) {
      print_info();
      return 0;
    }
    if (*drive) {
      // The perturbation flags are deck overrides, so resolved.yaml records them.
      if (*scale_opt) drive_overrides.push_back("drive.scale=" + fmt::format("{:.17g}", scale));
      if (*noise_opt) drive_overrides.push_back("drive.noise=" + fmt::format("{:.17g}", noise));
      if (*seed_opt) drive_overrides.push_back("drive.seed=" + (seed.empty() ? "''" : seed));  // '' fails, not 0
      const ballista::DriveDeck dd = ballista::read_drive_deck(drive_deck, drive_overrides);
      if (drive_out.empty()) drive_out = "out/" + std::filesystem::path(drive_deck).stem().string();
      const ballista::DriveRunResult r = ballista::run_drive(dd, drive_out);
      if (!r.ok) std::cerr << "drive failed: " << r.error << "\n";
      if (!drive_quiet || !r.ok) {
        const auto& s = r.last.sigma;
        std::cout << (r.ok ? "completed" : "FAILED") << ": " << r.steps << " steps to t = " << r.last.t << " s, "
                  << r.records << " records in " << fmt::format("{:.2f}", r.wall_seconds) << " s\n"
                  << fmt::format("  final sigma (11 22 33 23 13 12) = {:.6g} {:.6g} {:.6g} {:.6g} {:.6g} {:.6g} Pa\n",
                                 s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1))
                  << "results in " << std::filesystem::absolute(drive_out).string() << "\n";
      }
      return r.ok ? 0 : 3;
    }
    if (*run) {
      if (deck.empty() && restart_dir.empty()) throw ballista::Error("run: give a deck, or --restart DIR");
      if (!restart_dir.empty() && !out_dir.empty() &&
          std::filesystem::path(out_dir).lexically_normal() != std::filesystem::path(restart_dir).lexically_normal())
        throw ballista::Error("run: --restart continues in its own results folder; do not give -o");
      std::string restart_from;
      ballista::Scenario sc;
      // Rank 0 holds the results folder for the whole command: the run, its figures and a re-run
      // (io/run_folder.hpp); the other ranks learn whether it could.
      std::optional<ballista::RunFolder> folder;
      auto take_folder = [&](const std::string& dir, ballista::RunFolder::Mode mode) {
        std::string refused;
        if (world.rank() == 0) try {
            folder.emplace(dir, mode, overwrite);
          } catch (const std::exception& e) {
            refused = e.what();
          }
        if (world.distributed()) refused = world.broadcast(refused, 0);
        if (!refused.empty()) throw ballista::CollectiveError(refused);
      };
      if (!restart_dir.empty()) {
        take_folder(restart_dir, ballista::RunFolder::Mode::Continue);
        // The deck is the one the checkpoint was written with (its resolved text); --set still
        // applies, e.g. a later simulation.end_time.
        const auto [path, deck_text] = ballista::newest_checkpoint(restart_dir);
        restart_from = path;
        sc = ballista::parse_deck(deck_text, (std::filesystem::path(restart_dir) / "resolved.yaml").string(),
                                  overrides);
        out_dir = restart_dir;
        std::cerr << "restarting from " << path << "\n";
      } else {
        sc = ballista::read_deck(deck, overrides);
        if (out_dir.empty()) out_dir = "out/" + std::filesystem::path(deck).stem().string();
        take_folder(out_dir, ballista::RunFolder::Mode::NewRun);
      }
      ballista::RunOptions opt;
      opt.folder_held = true;
      opt.restart_from = restart_from;
      opt.checkpoint_minutes = checkpoint_minutes;
      opt.out_dir = out_dir;
      opt.threads = threads;
      opt.progress = !quiet;
      opt.plots = !no_plots;
      ballista::RunResult r = ballista::run_simulation(sc, opt);
      const auto& tracked = sc.output.track;
      if (!r.ok && track_failed && restart_dir.empty() && r.failed_particle >= 0 &&
          std::find(tracked.begin(), tracked.end(), r.failed_particle) == tracked.end()) {
        // Re-run from the start with the failing particle tracked: same deck, same thread count,
        // so the run is bitwise the same up to the failure (docs/deck.md, output.track).
        std::string ids;
        for (auto id : tracked) ids += std::to_string(id) + ",";
        ids += std::to_string(r.failed_particle);
        const long first_step = r.failed_step;
        const auto first_particle = r.failed_particle;
        std::cerr << "re-running with output.track.ids = [" << ids << "] to record the history of particle "
                  << first_particle << "\n";
        overrides.push_back("output.track.ids=[" + ids + "]");
        sc = ballista::read_deck(deck, overrides);
        if (folder) folder->clear();
        r = ballista::run_simulation(sc, opt);
        if (r.ok || r.failed_particle != first_particle || r.failed_step != first_step)
          std::cerr << "warning: the re-run did not fail the same way (particle " << r.failed_particle << " at step "
                    << r.failed_step << ", first run: particle " << first_particle << " at step " << first_step
                    << "): the run is not reproducible (different thread count?)\n";
        else
          std::cerr << "history of particle " << first_particle << " up to the failure: "
                    << (std::filesystem::path(out_dir) / "tracks" /
                        ("particle_" + std::to_string(first_particle) + ".csv"))
                           .string()
                    << " (replay: ballista drive with drive: {table: <that file>, substeps: 1})\n";
      }
      if (!r.checkpoint.empty())
        std::cout << (r.interrupted ? "checkpointed in " : "the last good step is checkpointed in ") << r.checkpoint
                  << " (ballista run --restart " << out_dir << ")\n";
      std::cout << (r.ok ? "completed" : r.interrupted ? "INTERRUPTED" : "FAILED") << ": " << r.steps
                << " steps to t = " << r.time << " s in "
                << fmt::format("{:.2f}", r.wall_seconds) << " s (" << fmt::format("{:.3g}", r.particle_steps_per_second)
                << " particle-steps/s)\n";
      for (const auto& [name, value] : r.probes) std::cout << "  " << name << " = " << value << "\n";
      if (sc.penetration.enabled && !no_plots && world.rank() == 0) {
        // Figures of the penetration run (thesis seed 000 Figs. 7.4-7.7), also after a failure:
        // what ran is worth seeing. A missing Python is a warning, not a failed run.
        const std::string err = ballista::make_penetration_plots(out_dir);
        if (err.empty())
          std::cout << "  figures: penetration_depth.png, penetration_rate.png, penetrator_energy.png, "
                       "channel_profile.png\n";
        else
          std::cerr << "warning: no penetration figures: " << err << " (--no-plots skips them)\n";
      }
      std::cout << "results in " << std::filesystem::absolute(out_dir).string() << "\n";
      return r.ok ? 0 : r.interrupted ? 4 : 3;
    }
  } catch (const ballista::DeckError& e) {
    // Every rank reads the same deck: rank 0 reports it.
    if (world.rank() == 0) report_error("deck error: ", e.what(), world);
    return 2;
  } catch (const ballista::CollectiveError& e) {
    if (world.rank() == 0) report_error("error: ", e.what(), world);
    return 1;
  } catch (const std::exception& e) {
    report_error("error: ", e.what(), world);
    return 1;
  }
  return 0;
}
