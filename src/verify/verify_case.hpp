#pragma once
// Result of one single-element verification test (`ballista verify`, verification CATALOGUE §A):
// what verify.json records per test and what tools/verify_report.py plots.
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace ballista {

enum class VerifyStatus { Pass, Fail, NotApplicable };

/// Every n-th entry of a per-step series and its last one: what a plot keeps of a long run.
std::vector<double> every_nth(const std::vector<double>& v, int n);
const char* to_string(VerifyStatus s);

/// One assertion inside a test: `value` compared with `limit` (value <= limit unless `at_least`).
struct VerifyCheck {
  std::string name;         ///< what is checked, one line
  double value = std::numeric_limits<double>::quiet_NaN();
  double limit = std::numeric_limits<double>::quiet_NaN();
  bool at_least = false;    ///< pass if value >= limit (a trend that must be visible)
  bool pass = false;
};

struct VerifyCase {
  std::string model;        ///< registered model name
  std::string test;         ///< test id: A1, A2, A2-iso, A2-kin, A3, A4, A5, A5-fluid, A6-objectivity, A6-tangent, A7, A8
  std::string title;        ///< one line: what the test is
  VerifyStatus status = VerifyStatus::NotApplicable;
  std::string reason;       ///< why not applicable, or what failed
  /// The headline comparison: maximum relative error against the analytic answer, its tolerance
  /// and a one-line justification of that tolerance.
  double max_rel_error = std::numeric_limits<double>::quiet_NaN();
  double tolerance = std::numeric_limits<double>::quiet_NaN();
  std::string error_measure;
  std::string tolerance_justification;
  std::vector<VerifyCheck> checks;  ///< all assertions, the headline one first
  /// Plot kind for tools/verify_report.py ("a1", "a2", "a3", "a4", "a5", "a5_fluid", "a6_objectivity",
  /// "a6_tangent", "a7", "a8"); empty for a test without a plot (not applicable).
  std::string plot;
  /// Named data series for the plot (equal lengths within a plot group; see the report tool).
  std::vector<std::pair<std::string, std::vector<double>>> series;
  /// Named scalars for the plot and the record (e.g. yield stress, tolerance lines).
  std::vector<std::pair<std::string, double>> scalars;
  double wall_seconds = 0.0;  ///< run time of the test, set by run_verify_test (0: not applicable)

  /// Adds a check (value <= limit, or value >= limit if at_least); returns its pass flag.
  bool check(std::string name, double value, double limit, bool at_least = false);
  /// Sets status from the checks: Pass if there is at least one and all pass, else Fail (with the
  /// failing checks listed in `reason`).
  void finish();
  static VerifyCase not_applicable(std::string model, std::string test, std::string title, std::string reason);
  /// A case about to be run: model, test id, title and plot kind set, no checks yet.
  static VerifyCase begin(std::string model, std::string test, std::string title, std::string plot);
};

}  // namespace ballista
