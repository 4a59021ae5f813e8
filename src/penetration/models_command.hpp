#pragma once
// The `models` subcommand of the command line (apps/ballista.cpp). Header-only: CLI11 is a
// dependency of the executable, not of the library.
#include <CLI/CLI.hpp>

#include "penetration/models_cli.hpp"

namespace ballista {

inline CLI::App* add_models_command(CLI::App& app, penetration::ModelsCliOptions& o) {
  auto* m = app.add_subcommand("models",
                               "analytic penetration models (Birkhoff, Eichelberger, Alekseevskii-Tate, ...): "
                               "'ballista models list', or 'ballista models NAME --param key=value ...' (SI units)");
  m->add_option("model", o.model, "'list' or a model name")->required();
  m->add_option("-p,--param", o.params, "model parameter key=value in SI units (repeatable)");
  m->add_option("--velocities", o.velocities, "sweep the impact velocity V over these values [m/s] (comma separated)")
      ->delimiter(',');
  m->add_option("--rates", o.rates, "penetration velocities U [m/s] paired with --velocities (fit models)")
      ->delimiter(',');
  m->add_option("--json", o.json_path, "also write the results to this JSON file");
  return m;
}

}  // namespace ballista
