#pragma once
// The `verify` subcommand of the command line (apps/ballista.cpp), kept here so that the CLI file
// only adds it and calls run_verify_cli. Header-only: CLI11 is a dependency of the executable,
// not of the library.
#include <CLI/CLI.hpp>

#include "verify/verify_cli.hpp"

namespace ballista {

inline CLI::App* add_verify_command(CLI::App& app, VerifyCliOptions& o) {
  auto* v = app.add_subcommand("verify",
                               "single-element verification suite (CATALOGUE A1-A8) of every registered "
                               "model: DIR/verify.json and DIR/report.html; exit 1 if a test fails");
  v->add_option("-o,--output", o.out_dir, "results folder (default out/verify)");
  v->add_option("--model", o.models, "only this model (repeatable)");
  v->add_option("--test", o.tests,
                "only this test: A1, A2, A2-iso, A2-kin, A3, A4, A5, A5-fluid, A6-objectivity, A6-tangent, A7, A8 "
                "(repeatable)");
  v->add_option("--threads", o.threads, "tests run concurrently on this many threads (default: all cores)");
  v->add_flag_callback("--no-report", [&o] { o.report = false; }, "write verify.json only (no Python needed)");
  v->add_flag("-q,--quiet", o.quiet, "list only the failed tests");
  return v;
}

}  // namespace ballista
