#include "verify/verify_cli.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <sys/wait.h>

#include <fmt/format.h>

#include "core/parallel.hpp"
#include "io/atomic_file.hpp"
#include "materials/material.hpp"
#include "verify/verify_json.hpp"
#include "verify/verify_suite.hpp"

#ifndef BALLISTA_PYTHON
#define BALLISTA_PYTHON "/usr/bin/python3"
#endif
#ifndef BALLISTA_SOURCE_DIR
#define BALLISTA_SOURCE_DIR "."
#endif
#ifndef BALLISTA_VERSION
#define BALLISTA_VERSION "unknown"
#endif

namespace ballista {

namespace fs = std::filesystem;

std::string verify_python() {
  // The configured interpreter (CMake cache BALLISTA_PYTHON, as the tests use it); the environment
  // variable of the same name overrides it (another Python, or a test of the error path).
  const char* env = std::getenv("BALLISTA_PYTHON");
  return env && *env ? std::string(env) : std::string(BALLISTA_PYTHON);
}
std::string verify_report_script() { return (fs::path(BALLISTA_SOURCE_DIR) / "tools" / "verify_report.py").string(); }

namespace {

/// A single-quoted shell word.
std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// Exit status of a std::system call (-1 if it did not run or was killed).
int run_command(const std::string& cmd) {
  const int rc = std::system(cmd.c_str());
  if (rc == -1) return -1;
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

}  // namespace

std::string make_verify_report(const std::string& out_dir) {
  const std::string py = verify_python(), script = verify_report_script();
  if (!fs::exists(py))
    return fmt::format("the report needs Python with matplotlib: interpreter {} (BALLISTA_PYTHON) does not exist; "
                       "configure with -DBALLISTA_PYTHON=/path/to/python3, set BALLISTA_PYTHON in the environment, "
                       "or use --no-report",
                       py);
  if (run_command(shell_quote(py) + " -c 'import matplotlib, numpy' >/dev/null 2>&1") != 0)
    return fmt::format("the report needs matplotlib and numpy: {} (BALLISTA_PYTHON) cannot import them (Debian: "
                       "apt install python3-matplotlib python3-numpy; or point BALLISTA_PYTHON at another Python; "
                       "or use --no-report)",
                       py);
  if (!fs::exists(script)) return "report script " + script + " not found (BALLISTA_SOURCE_DIR moved?)";
  const std::string json = (fs::path(out_dir) / "verify.json").string();
  const int rc = run_command(shell_quote(py) + " " + shell_quote(script) + " " + shell_quote(json));
  if (rc != 0) return fmt::format("{} {} {} failed with status {}", py, script, json, rc);
  return {};
}

int run_verify_cli(const VerifyCliOptions& o) {
  fs::create_directories(o.out_dir);
  VerifySuiteOptions so;
  so.models = o.models;
  so.tests = o.tests;
  so.threads = o.threads;
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<MaterialFactory> factories = material_registry();  // a copy: read once, on this thread
  const std::vector<VerifyCase> cases = run_verify_suite(factories, so);
  VerifyRunInfo info;
  info.version = BALLISTA_VERSION;
  info.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  info.threads = o.threads > 0 ? o.threads : max_threads();
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
