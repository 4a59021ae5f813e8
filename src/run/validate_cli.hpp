#pragma once
// `ballista validate`: the V&V report. The problems, their references and bounds are data
// (data/validation_catalogue.yaml); tools/validate.py runs them with this executable and writes
// DIR/validate.json and the self-contained DIR/report.html.
#include <string>
#include <vector>

namespace ballista {

struct ValidateCliOptions {
  std::string out_dir = "out/validate";
  std::string level = "quick";    ///< quick (CI sizes) or full (the documented sizes)
  std::vector<std::string> only;  ///< --only ID (repeatable)
  std::vector<std::string> skip;  ///< --skip ID (repeatable)
  bool list = false;              ///< --list: the problems and their levels
  int threads = 0;                ///< --threads per run (0: each run's default)
};

/// Runs tools/validate.py with this executable (`argv0`, resolved through /proc/self/exe).
/// Returns its status: 0 every problem passed, 1 a check or a run failed, 2 the report could not
/// be made (Python, the tool or the catalogue missing; a bad --only).
int run_validate_cli(const ValidateCliOptions& o, const char* argv0);

}  // namespace ballista
