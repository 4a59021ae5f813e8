#pragma once
// `ballista verify [-o DIR]`: runs the single-element verification suite (verify_suite.hpp),
// writes DIR/verify.json and, through tools/verify_report.py, DIR/report.html with one PNG per
// test in DIR/plots/. See docs/validation.md, "Single-element verification (ballista verify)".
#include <string>
#include <vector>

namespace ballista {

struct VerifyCliOptions {
  std::string out_dir = "out/verify";
  std::vector<std::string> models;  ///< only these models (empty: all registered)
  std::vector<std::string> tests;   ///< only these tests (empty: all)
  int threads = 0;                  ///< 0: all cores
  bool report = true;               ///< false: verify.json only (no Python needed)
  bool quiet = false;               ///< no per-test table on stdout
};

/// Exit status of `ballista verify`.
enum VerifyExit : int {
  kVerifyAllPassed = 0,
  kVerifyTestFailed = 1,    ///< at least one test failed (verify.json and the report are still written)
  kVerifyReportFailed = 4,  ///< every test passed but the HTML/PNG report could not be made
};

int run_verify_cli(const VerifyCliOptions& options);

/// The interpreter the report uses (BALLISTA_PYTHON, set by CMake; the environment variable of the
/// same name overrides it) and the report script (tools/verify_report.py in the source tree).
std::string verify_python();
std::string verify_report_script();

/// Runs the report script on DIR/verify.json; returns an empty string on success, else a message
/// saying what is missing (interpreter, matplotlib, the script) or how the script failed.
std::string make_verify_report(const std::string& out_dir);

}  // namespace ballista
