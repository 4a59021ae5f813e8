#pragma once
// verify.json: the record of a `ballista verify` run (one object per test, see docs/validation.md,
// "Single-element verification"). Written by hand (no JSON library among the dependencies);
// non-finite numbers become null.
#include <string>
#include <vector>

#include "verify/verify_case.hpp"

namespace ballista {

struct VerifyRunInfo {
  std::string version;       ///< Ballista version
  double wall_seconds = 0.0; ///< time of the test runs (without the report)
  int threads = 1;
};

/// The JSON text of a run.
std::string verify_json(const std::vector<VerifyCase>& cases, const VerifyRunInfo& info);

/// A JSON string literal (quotes, backslashes and control characters escaped).
std::string json_quote(const std::string& s);
/// A JSON number (shortest round-trip form) or null if not finite.
std::string json_number(double x);

}  // namespace ballista
