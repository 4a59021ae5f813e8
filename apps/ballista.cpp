// The `ballista` command line: run a deck, list what is registered.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "core/error.hpp"
#include "io/deck_reader.hpp"
#include "materials/material.hpp"
#include "mpm/shape_functions.hpp"
#include "run/simulation.hpp"
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

void print_info() {
  std::cout << "Ballista " << BALLISTA_VERSION << "\n\nSolvers\n";
  std::cout << "  mpm  explicit material point method (Sulsky et al. 1994; USL / modified USL,\n"
               "       FLIP/PIC blend); dimensions 3d, plane_strain, axisymmetric\n"
               "      shape_function         [-] linear | gimp | cpdi | bspline3; default linear\n"
               "      update                 [-] usl | musl; default musl (robust against cell-crossing at free surfaces)\n"
               "      flip                   [1] FLIP fraction of the velocity update (1 FLIP, 0 PIC); default 1; range 0 <= x <= 1\n"
               "      sort_every             [steps] steps between particle sorts by cell (0 = never); default 20\n"
               "      simulation.cfl         [1] Courant number of dt = cfl h / max(c + |v|); default 0.3; range 0 < x <= 1\n"
               "      simulation.damping     [1/s] grid damping a - c v (dynamic relaxation); default 0\n";
  std::cout << "\nShape functions (mpm.shape_function)\n";
  for (const auto& n : ballista::shape_kind_names())
    std::cout << "  " << n << "  " << ballista::shape_kind_description(ballista::parse_shape_kind(n)) << "\n";
  std::cout << "\nMaterials (materials.<name>.model)\n";
  for (const auto& f : ballista::material_registry()) {
    std::cout << "  " << f.model << "  " << f.description << "\n";
    for (const auto& p : f.params)
      std::cout << fmt::format("      {:<22} [{}] {}; {}{}\n", p.name, p.unit, p.description,
                               format_default(p),
                               format_range(p).empty() ? "" : "; range " + format_range(p));
    if (!f.state_fields.empty()) {
      std::cout << "      state fields:";
      for (const auto& s : f.state_fields) std::cout << " " << s.name << " [" << s.unit << "]";
      std::cout << "\n";
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ballista: solids under extreme deformation (MPM; peridynamics and OTM planned)"};
  app.set_version_flag("--version", std::string("ballista ") + BALLISTA_VERSION);
  app.require_subcommand(1);

  auto* run = app.add_subcommand("run", "run a deck");
  std::string deck, out_dir;
  int threads = 0;
  std::vector<std::string> overrides;
  bool quiet = false;
  run->add_option("deck", deck, "YAML deck file")->required()->check(CLI::ExistingFile);
  run->add_option("-o,--output", out_dir, "results folder (default out/<deck name>)");
  run->add_option("--threads", threads, "OpenMP threads (default: the deck's, else all cores)");
  run->add_option("--set", overrides, "override a deck value: key.path=value (repeatable)");
  run->add_flag("-q,--quiet", quiet, "no progress output");

  auto* info = app.add_subcommand("info", "list registered solvers, shape functions and materials");
  ballista::VerifyCliOptions verify_opt;
  auto* verify = ballista::add_verify_command(app, verify_opt);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*verify) return ballista::run_verify_cli(verify_opt);
    if (*info) {
      print_info();
      return 0;
    }
    if (*run) {
      const ballista::Scenario sc = ballista::read_deck(deck, overrides);
      if (out_dir.empty()) out_dir = "out/" + std::filesystem::path(deck).stem().string();
      ballista::RunOptions opt;
      opt.out_dir = out_dir;
      opt.threads = threads;
      opt.progress = !quiet;
      const ballista::RunResult r = ballista::run_simulation(sc, opt);
      std::cout << (r.ok ? "completed" : "FAILED") << ": " << r.steps << " steps to t = " << r.time
                << " s in " << fmt::format("{:.2f}", r.wall_seconds) << " s ("
                << fmt::format("{:.3g}", r.particle_steps_per_second) << " particle-steps/s)\n";
      for (const auto& [name, value] : r.probes) std::cout << "  " << name << " = " << value << "\n";
      std::cout << "results in " << std::filesystem::absolute(out_dir).string() << "\n";
      return r.ok ? 0 : 3;
    }
  } catch (const ballista::DeckError& e) {
    std::cerr << "deck error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
