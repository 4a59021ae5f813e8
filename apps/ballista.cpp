// The `ballista` command line: run a deck, drive a single material point, list what is registered.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "core/build_info.hpp"
#include "core/communicator.hpp"
#include "core/console_log.hpp"
#include "core/data_dir.hpp"
#include "core/error.hpp"
#include "core/threads.hpp"
#include "deck/material_presets.hpp"
#include "driver/drive_run.hpp"
#include "io/atomic_file.hpp"
#include "materials/material.hpp"
#include "mpm/shape_functions.hpp"
#include "penetration/models_command.hpp"
#include "points/initial_state_registry.hpp"
#include "points/load_registry.hpp"
#include "points/probe_registry.hpp"
#include "points/solver_registry.hpp"
#include "run/deck_schema.hpp"
#include "run/sweep_command.hpp"
#include "run/validate_command.hpp"
#include "run_command.hpp"
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
  std::cout << "Ballista " << BALLISTA_VERSION << " (" << ballista::build_commit() << ")\n"
            << "Data directory (presets and tools; " << ballista::data_dir_origin()
            << "): " << ballista::data_dir()
            << "\n\nSolvers (simulation.solver; parameters in the section named)\n";
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

/// The options of `ballista drive`, as CLI11 fills them.
struct DriveCliOptions {
  std::string deck, out_dir;
  std::vector<std::string> overrides;
  double scale = 1.0, noise = 0.0;
  std::string seed;  // validated as the deck key drive.seed, with its message (one check, one wording)
  bool quiet = false;
  // Whether --scale, --noise and --seed were given (they become deck overrides).
  CLI::Option* scale_opt = nullptr;
  CLI::Option* noise_opt = nullptr;
  CLI::Option* seed_opt = nullptr;
};

/// Adds the `drive` subcommand to `app`, its options filling `o`.
CLI::App* add_drive_command(CLI::App& app, DriveCliOptions& o) {
  auto* drive = app.add_subcommand("drive", "drive one material point through an F-table or strain/stress legs");
  drive->add_option("deck", o.deck, "YAML drive deck (materials + drive)")->required()->check(CLI::ExistingFile);
  drive->add_option("-o,--output", o.out_dir, "results folder (default out/<deck name>)");
  drive->add_option(
      "--set", o.overrides,
      "override a deck value: key.path=value, or append to a list: key.path+=value (repeatable)");
  o.scale_opt = drive->add_option(
      "--scale", o.scale, "scale the table's deformation: F -> I + S (F - I) (drive.scale)");
  o.noise_opt = drive->add_option("--noise", o.noise,
                                  "multiplicative noise of amplitude A on the table's increments (drive.noise)");
  o.seed_opt = drive->add_option("--seed", o.seed, "seed of the noise (drive.seed; 0 <= seed < 2^63)");
  o.seed_opt->needs(o.noise_opt);
  drive->add_flag("-q,--quiet", o.quiet, "print nothing on success");
  return drive;
}

/// Runs `ballista drive` and returns its exit code (0 done, 3 failed); deck errors are thrown.
int run_drive_cli(DriveCliOptions o) {
  // The perturbation flags are deck overrides, so resolved.yaml records them.
  if (*o.scale_opt) o.overrides.push_back("drive.scale=" + fmt::format("{:.17g}", o.scale));
  if (*o.noise_opt) o.overrides.push_back("drive.noise=" + fmt::format("{:.17g}", o.noise));
  if (*o.seed_opt) o.overrides.push_back("drive.seed=" + (o.seed.empty() ? "''" : o.seed));  // '' fails, not 0
  const ballista::DriveDeck dd = ballista::read_drive_deck(o.deck, o.overrides);
  if (o.out_dir.empty()) o.out_dir = "out/" + std::filesystem::path(o.deck).stem().string();
  const ballista::DriveRunResult r = ballista::run_drive(dd, o.out_dir);
  if (!r.ok) std::cerr << "drive failed: " << r.error << "\n";
  if (!o.quiet || !r.ok) {
    const auto& s = r.last.sigma;
    std::cout << (r.ok ? "completed" : "FAILED") << ": " << r.steps << " steps to t = " << r.last.t << " s, "
              << r.records << " records in " << fmt::format("{:.2f}", r.wall_seconds) << " s\n"
              << fmt::format("  final sigma (11 22 33 23 13 12) = {:.6g} {:.6g} {:.6g} {:.6g} {:.6g} {:.6g} Pa\n",
                             s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1))
              << "results in " << std::filesystem::absolute(o.out_dir).string() << "\n";
  }
  return r.ok ? 0 : 3;
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
  // Diagnostics on standard error, results on standard output (core/console_log.hpp).
  ballista::log_to_stderr();
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
  app.set_version_flag("--version", std::string("ballista ") + BALLISTA_VERSION + " (" +
                                        ballista::build_commit() + ")");
  app.require_subcommand(1);

  ballista::RunCliOptions run_opt;
  auto* run = ballista::add_run_command(app, run_opt);
  DriveCliOptions drive_opt;
  auto* drive = add_drive_command(app, drive_opt);
  auto* info = app.add_subcommand("info", "list registered solvers, shape functions and materials");
  std::string schema_out;
  std::vector<std::string> schema_decks;
  auto* schema = app.add_subcommand(
      "schema", "print the JSON Schema of run decks (for an editor's YAML language server; docs/deck.md), made "
                "from the deck readers by reading the shipped examples (or the decks given) and from the registries");
  schema->add_option("decks", schema_decks, "run decks to read (default: the shipped examples)")
      ->check(CLI::ExistingFile);
  schema->add_option("-o,--output", schema_out, "write the schema to this file instead of standard output");
  ballista::VerifyCliOptions verify_opt;
  auto* verify = ballista::add_verify_command(app, verify_opt);
  ballista::penetration::ModelsCliOptions models_opt;
  auto* models = ballista::add_models_command(app, models_opt);
  ballista::SweepCliOptions sweep_opt;
  auto* sweep = ballista::add_sweep_command(app, sweep_opt);
  ballista::ValidateCliOptions validate_opt;
  auto* validate = ballista::add_validate_command(app, validate_opt);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*verify) return ballista::run_verify_cli(verify_opt);
    if (*models) return ballista::penetration::run_models_cli(models_opt);
    if (*sweep) return ballista::run_sweep_cli(sweep_opt, argv[0]);
    if (*validate) return ballista::run_validate_cli(validate_opt, argv[0]);
    if (*info) {
      print_info();
      return 0;
    }
    if (*schema) {
      const std::string text =
          ballista::deck_schema(schema_decks.empty() ? ballista::example_run_decks() : schema_decks);
      if (schema_out.empty())
        std::cout << text;
      else
        ballista::write_file_atomic(schema_out, text);
      return 0;
    }
    if (*drive) return run_drive_cli(drive_opt);
    if (*run) return ballista::run_deck_cli(run_opt, world);
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
