#include "verify/verify_cli.hpp"

#include <chrono>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "core/parallel.hpp"
#include "core/threads.hpp"
#include "io/atomic_file.hpp"
#include "io/python_tool.hpp"
#include "materials/material.hpp"
#include "verify/verify_json.hpp"
#include "verify/verify_suite.hpp"

#ifndef BALLISTA_VERSION
#define BALLISTA_VERSION "unknown"
#endif

namespace ballista {

namespace fs = std::filesystem;

std::string verify_python() { return python_interpreter(); }
std::string verify_report_script() { return python_tool_path("verify_report.py"); }

std::string make_verify_report(const std::string& out_dir) {
  return run_python_tool("verify_report.py", {(fs::path(out_dir) / "verify.json").string()}, "the report",
                         "or use --no-report");
}

int run_verify_cli(const VerifyCliOptions& o) {
  fs::create_directories(o.out_dir);
  VerifySuiteOptions so;
  so.models = o.models;
  so.tests = o.tests;
  // --threads above the cores is clamped with a warning, as for `ballista run` (core/threads.hpp).
  so.threads = o.threads > 0 ? request_threads(o.threads, "--threads") : o.threads;
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<MaterialFactory> factories = material_registry();  // a copy: read once, on this thread
  const std::vector<VerifyCase> cases = run_verify_suite(factories, so);
  VerifyRunInfo info;
  info.version = BALLISTA_VERSION;
  info.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  info.threads = so.threads > 0 ? so.threads : max_threads();
  const std::string json_path = (fs::path(o.out_dir) / "verify.json").string();
  write_file_atomic(json_path, verify_json(cases, info));

  int n_fail = 0, n_pass = 0, n_na = 0;
  for (const VerifyCase& c : cases) {
    if (c.status == VerifyStatus::Fail) ++n_fail;
    else if (c.status == VerifyStatus::Pass) ++n_pass;
    else ++n_na;
    if (o.quiet && c.status != VerifyStatus::Fail) continue;
    std::cout << fmt::format("{:<16} {:<15} {:<15} ", c.model, c.test, to_string(c.status));
    if (c.status == VerifyStatus::NotApplicable)
      std::cout << c.reason << "\n";
    else
      std::cout << fmt::format("max rel error {:9.2e}  tolerance {:8.1e}{}\n", c.max_rel_error, c.tolerance,
                               c.status == VerifyStatus::Fail ? "  " + c.reason : "");
  }
  std::cout << fmt::format("verify: {} passed, {} failed, {} not applicable in {:.1f} s; {}\n", n_pass, n_fail, n_na,
                           info.wall_seconds, fs::absolute(json_path).string());
  int status = n_fail > 0 ? kVerifyTestFailed : kVerifyAllPassed;
  if (o.report) {
    const std::string err = make_verify_report(o.out_dir);
    if (!err.empty()) {
      std::cerr << "verify: report not written: " << err << "\n";
      if (status == kVerifyAllPassed) status = kVerifyReportFailed;
    } else {
      std::cout << "report: " << fs::absolute(fs::path(o.out_dir) / "report.html").string() << "\n";
    }
  }
  return status;
}

}  // namespace ballista
