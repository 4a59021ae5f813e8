#include "verify/verify_json.hpp"

#include <cmath>

#include <fmt/format.h>

#include "io/summary_writer.hpp"

namespace ballista {

std::string json_quote(const std::string& s) {
  std::string out;
  json_escape_to(out, s);  // the run summary's escaping (io/summary_writer)
  return out;
}

std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  return fmt::format("{}", x);  // fmt's default: shortest representation that round-trips
}

namespace {

std::string number_array(const std::vector<double>& v) {
  std::string out = "[";
  for (size_t k = 0; k < v.size(); ++k) out += (k ? "," : "") + json_number(v[k]);
  return out + "]";
}

std::string case_json(const VerifyCase& c) {
  std::string o = "    {\n";
  o += "      \"model\": " + json_quote(c.model) + ",\n";
  o += "      \"test\": " + json_quote(c.test) + ",\n";
  o += "      \"title\": " + json_quote(c.title) + ",\n";
  o += "      \"status\": " + json_quote(to_string(c.status)) + ",\n";
  o += "      \"passed\": " + std::string(c.status == VerifyStatus::Pass ? "true" : "false") + ",\n";
  o += "      \"reason\": " + json_quote(c.reason) + ",\n";
  o += "      \"max_rel_error\": " + json_number(c.max_rel_error) + ",\n";
  o += "      \"tolerance\": " + json_number(c.tolerance) + ",\n";
  o += "      \"error_measure\": " + json_quote(c.error_measure) + ",\n";
  o += "      \"tolerance_justification\": " + json_quote(c.tolerance_justification) + ",\n";
  o += "      \"wall_seconds\": " + json_number(c.wall_seconds) + ",\n";
  o += "      \"checks\": [";
  for (size_t k = 0; k < c.checks.size(); ++k) {
    const VerifyCheck& ch = c.checks[k];
    o += std::string(k ? "," : "") + "\n        {\"name\": " + json_quote(ch.name) +
         ", \"value\": " + json_number(ch.value) + ", \"limit\": " + json_number(ch.limit) +
         ", \"kind\": " + json_quote(ch.at_least ? ">=" : "<=") + ", \"pass\": " + (ch.pass ? "true" : "false") + "}";
  }
  o += c.checks.empty() ? "],\n" : "\n      ],\n";
  o += "      \"plot\": " + (c.plot.empty() ? std::string("null") : json_quote(c.plot)) + ",\n";
  o += "      \"scalars\": {";
  for (size_t k = 0; k < c.scalars.size(); ++k)
    o += std::string(k ? ", " : "") + json_quote(c.scalars[k].first) + ": " + json_number(c.scalars[k].second);
  o += "},\n";
  o += "      \"series\": {";
  for (size_t k = 0; k < c.series.size(); ++k)
    o += std::string(k ? "," : "") + "\n        " + json_quote(c.series[k].first) + ": " +
         number_array(c.series[k].second);
  o += c.series.empty() ? "}\n" : "\n      }\n";
  return o + "    }";
}

}  // namespace

std::string verify_json(const std::vector<VerifyCase>& cases, const VerifyRunInfo& info) {
  int n_pass = 0, n_fail = 0, n_na = 0;
  for (const VerifyCase& c : cases) {
    if (c.status == VerifyStatus::Pass) ++n_pass;
    else if (c.status == VerifyStatus::Fail) ++n_fail;
    else ++n_na;
  }
  std::string o = "{\n";
  o += "  \"format\": \"ballista-verify-1\",\n";
  o += "  \"ballista_version\": " + json_quote(info.version) + ",\n";
  o += "  \"catalogue\": \"verification CATALOGUE section A (single-element problems)\",\n";
  o += "  \"wall_seconds\": " + json_number(info.wall_seconds) + ",\n";
  o += "  \"threads\": " + std::to_string(info.threads) + ",\n";
  o += fmt::format("  \"summary\": {{\"pass\": {}, \"fail\": {}, \"not_applicable\": {}, \"all_passed\": {}}},\n",
                   n_pass, n_fail, n_na, n_fail == 0 ? "true" : "false");
  o += "  \"tests\": [\n";
  for (size_t k = 0; k < cases.size(); ++k) o += case_json(cases[k]) + (k + 1 < cases.size() ? ",\n" : "\n");
  return o + "  ]\n}\n";
}

}  // namespace ballista
