#pragma once
// The `validate` subcommand of the command line (apps/ballista.cpp). Header-only: CLI11 is a
// dependency of the executable, not of the library.
#include <CLI/CLI.hpp>

#include "run/validate_cli.hpp"

namespace ballista {

inline CLI::App* add_validate_command(CLI::App& app, ValidateCliOptions& o) {
  auto* v = app.add_subcommand(
      "validate",
      "the V&V report: run the verification and validation problems of docs/validation.md "
      "(data/validation_catalogue.yaml) at one level, check each against its reference's bound, and write "
      "DIR/validate.json and a self-contained DIR/report.html; exit 1 if a check fails");
  v->add_option("-o,--output", o.out_dir, "report folder (default out/validate)");
  v->add_option("--level", o.level, "quick (CI sizes, seconds) or full (the documented sizes, tens of minutes)")
      ->check(CLI::IsMember({"quick", "full"}));
  v->add_option("--only", o.only, "only this problem (repeatable; --list names them)");
  v->add_option("--skip", o.skip, "not this problem (repeatable)");
  v->add_flag("--list", o.list, "list the problems and the levels they run at");
  v->add_option("--threads", o.threads, "OpenMP threads per run (default: each run's own)")
      ->check(CLI::PositiveNumber);
  return v;
}

}  // namespace ballista
