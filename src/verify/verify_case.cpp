#include "verify/verify_case.hpp"

#include <cmath>
#include <utility>

#include <fmt/format.h>

namespace ballista {

const char* to_string(VerifyStatus s) {
  switch (s) {
    case VerifyStatus::Pass: return "pass";
    case VerifyStatus::Fail: return "fail";
    case VerifyStatus::NotApplicable: return "not_applicable";
  }
  return "?";
}

std::vector<double> every_nth(const std::vector<double>& v, int n) {
  std::vector<double> o;
  for (size_t k = 0; k < v.size(); ++k)
    if (k % static_cast<size_t>(n) == 0 || k + 1 == v.size()) o.push_back(v[k]);
  return o;
}

bool VerifyCase::check(std::string name, double value, double limit, bool at_least) {
  // NaN fails either way (a non-finite result must never pass).
  const bool ok = at_least ? value >= limit : value <= limit;
  checks.push_back({std::move(name), value, limit, at_least, ok});
  return ok;
}

void VerifyCase::finish() {
  std::string failed;
  for (const VerifyCheck& c : checks)
    if (!c.pass)
      failed += fmt::format("{}{} ({:.3g} {} {:.3g})", failed.empty() ? "" : "; ", c.name, c.value,
                            c.at_least ? "<" : ">", c.limit);
  if (checks.empty()) {
    status = VerifyStatus::Fail;
    if (reason.empty()) reason = "no check was made";
  } else if (failed.empty()) {
    status = VerifyStatus::Pass;
  } else {
    status = VerifyStatus::Fail;
    reason = reason.empty() ? "failed: " + failed : reason + "; failed: " + failed;
  }
}

VerifyCase VerifyCase::not_applicable(std::string model, std::string test, std::string title, std::string reason) {
  VerifyCase c;
  c.model = std::move(model);
  c.test = std::move(test);
  c.title = std::move(title);
  c.status = VerifyStatus::NotApplicable;
  c.reason = std::move(reason);
  return c;
}

VerifyCase VerifyCase::begin(std::string model, std::string test, std::string title, std::string plot) {
  VerifyCase c;
  c.model = std::move(model);
  c.test = std::move(test);
  c.title = std::move(title);
  c.plot = std::move(plot);
  return c;
}

}  // namespace ballista
