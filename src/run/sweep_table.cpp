#include "run/sweep_table.hpp"

#include <charconv>
#include <cmath>
#include <set>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/history_writer.hpp"

namespace ballista {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

[[noreturn]] void vary_error(const std::string& text, const std::string& what) {
  throw Error("--vary '" + text + "': " + what + " (expected key.path=value1,value2,...)");
}

void flatten_into(const YAML::Node& n, const std::string& prefix, std::vector<std::pair<std::string, SweepCell>>& out) {
  switch (n.Type()) {
    case YAML::NodeType::Map:
      for (const auto& kv : n) {
        const std::string k = kv.first.as<std::string>();
        flatten_into(kv.second, prefix.empty() ? k : prefix + "." + k, out);
      }
      return;
    case YAML::NodeType::Sequence:
      for (size_t i = 0; i < n.size(); ++i) flatten_into(n[i], prefix + "." + std::to_string(i), out);
      return;
    case YAML::NodeType::Scalar: {
      // A quoted JSON string has the non-specific tag "!"; keep it a string even if it looks
      // numeric.
      SweepCell c = n.Tag() == "!" ? SweepCell{n.Scalar(), SweepCell::Kind::String} : sweep_cell(n.Scalar());
      out.emplace_back(prefix, std::move(c));
      return;
    }
    default:
      return;  // null / undefined: an empty cell
  }
}

JsonValue cell_json(const SweepCell& c) {
  switch (c.kind) {
    case SweepCell::Kind::Number: {
      double v = 0;  // sweep_cell checked that the whole text parses
      std::from_chars(c.text.data(), c.text.data() + c.text.size(), v);
      return JsonValue(v);
    }
    case SweepCell::Kind::Bool:
      return JsonValue(c.text == "true");
    case SweepCell::Kind::String:
      return JsonValue(c.text);
  }
  return JsonValue();
}

}  // namespace

SweepAxis parse_vary(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) vary_error(text, "no '='");
  SweepAxis axis;
  axis.key = trim(text.substr(0, eq));
  if (axis.key.empty()) vary_error(text, "empty key path");
  if (axis.key.back() == '+')
    vary_error(text, "'+=' cannot be varied; append in every run with --set key.path+=value");
  if (axis.key.front() == '.' || axis.key.back() == '.' || axis.key.find("..") != std::string::npos)
    vary_error(text, "empty component in key path '" + axis.key + "'");
  const std::string list = text.substr(eq + 1);
  if (trim(list).empty()) vary_error(text, "empty value list");
  // Split at commas at bracket depth 0 outside quotes, so flow lists and maps stay one value.
  int depth = 0;
  char quote = 0;
  std::string cur;
  const auto finish = [&] {
    const std::string v = trim(cur);
    if (v.empty()) vary_error(text, "empty value (value " + std::to_string(axis.values.size() + 1) + ")");
    axis.values.push_back(v);
    cur.clear();
  };
  for (char c : list) {
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      if (--depth < 0) vary_error(text, std::string("unbalanced '") + c + "'");
    } else if (c == ',' && depth == 0) {
      finish();
      continue;
    }
    cur += c;
  }
  if (quote) vary_error(text, std::string("unterminated quote ") + quote);
  if (depth != 0) vary_error(text, "unbalanced brackets");
  finish();
  return axis;
}

std::vector<SweepAxis> parse_vary_options(const std::vector<std::string>& texts) {
  std::vector<SweepAxis> axes;
  std::set<std::string> keys;
  for (const auto& t : texts) {
    SweepAxis a = parse_vary(t);
    if (!keys.insert(a.key).second) throw Error("--vary '" + t + "': key '" + a.key + "' is varied twice");
    axes.push_back(std::move(a));
  }
  return axes;
}

std::vector<std::vector<std::string>> sweep_product(const std::vector<SweepAxis>& axes) {
  std::vector<std::vector<std::string>> runs{{}};
  for (const SweepAxis& a : axes) {  // each axis multiplies the runs so far; the last varies fastest
    std::vector<std::vector<std::string>> next;
    next.reserve(runs.size() * a.values.size());
    for (const auto& prefix : runs)
      for (const auto& v : a.values) {
        next.push_back(prefix);
        next.back().push_back(v);
      }
    runs = std::move(next);
  }
  return runs;
}

SweepCell sweep_cell(const std::string& text) {
  if (text == "true" || text == "false") return {text, SweepCell::Kind::Bool};
  double v = 0;
  const char* end = text.data() + text.size();
  const auto r = std::from_chars(text.data(), end, v);
  if (!text.empty() && r.ec == std::errc() && r.ptr == end && std::isfinite(v)) return {text, SweepCell::Kind::Number};
  return {text, SweepCell::Kind::String};
}

std::vector<std::pair<std::string, SweepCell>> flatten_summary(const YAML::Node& summary,
                                                               const std::vector<std::string>& skip) {
  std::vector<std::pair<std::string, SweepCell>> out;
  if (!summary.IsMap()) return out;
  for (const auto& kv : summary) {
    const std::string k = kv.first.as<std::string>();
    bool skipped = false;
    for (const auto& s : skip) skipped = skipped || s == k;
    if (!skipped) flatten_into(kv.second, k, out);
  }
  return out;
}

std::vector<std::string> SweepTable::summary_columns() const {
  std::vector<std::string> cols;
  std::set<std::string> seen;
  for (const SweepRow& r : rows_)
    for (const auto& [name, cell] : r.scalars)
      if (seen.insert(name).second) cols.push_back(name);
  return cols;
}

std::vector<std::string> SweepTable::columns() const {
  std::vector<std::string> cols{"run"};
  for (const auto& a : axes_) cols.push_back(a.key);
  cols.push_back("status");
  cols.push_back("error");
  for (auto& c : summary_columns()) cols.push_back(std::move(c));
  return cols;
}

int SweepTable::failed() const {
  int n = 0;
  for (const SweepRow& r : rows_) n += r.status != "completed";
  return n;
}

std::string SweepTable::csv() const {
  const std::vector<std::string> cols = columns();
  const std::vector<std::string> sum = summary_columns();
  std::string out;
  for (size_t k = 0; k < cols.size(); ++k) out += (k ? "," : "") + csv_quote(cols[k]);
  out += '\n';
  for (const SweepRow& r : rows_) {
    out += std::to_string(r.index);
    for (size_t a = 0; a < axes_.size(); ++a) out += "," + csv_quote(a < r.values.size() ? r.values[a] : "");
    out += "," + csv_quote(r.status) + "," + csv_quote(r.error);
    for (const auto& c : sum) {
      out += ',';
      for (const auto& [name, cell] : r.scalars)
        if (name == c) {
          out += csv_quote(cell.text);
          break;
        }
    }
    out += '\n';
  }
  return out;
}

JsonValue SweepTable::json() const {
  JsonValue j = JsonValue::object();
  JsonValue& axes = j["axes"];
  axes = JsonValue::array();
  for (const auto& a : axes_) {
    JsonValue& e = axes.push_back(JsonValue::object());
    e["key"] = a.key;
    e["values"] = a.values;
  }
  j["columns"] = columns();
  JsonValue& runs = j["runs"];
  runs = JsonValue::array();
  const std::vector<std::string> sum = summary_columns();
  for (const SweepRow& r : rows_) {
    JsonValue& o = runs.push_back(JsonValue::object());
    o["run"] = r.index;
    for (size_t a = 0; a < axes_.size(); ++a)
      o[axes_[a].key] = a < r.values.size() ? cell_json(sweep_cell(r.values[a])) : JsonValue();
    o["status"] = r.status;
    o["error"] = r.error.empty() ? JsonValue() : JsonValue(r.error);
    for (const auto& c : sum) {
      JsonValue v;  // null when this run has no such column
      for (const auto& [name, cell] : r.scalars)
        if (name == c) {
          v = cell_json(cell);
          break;
        }
      o[c] = std::move(v);
    }
  }
  return j;
}

void SweepTable::write(const std::filesystem::path& out_dir) const {
  std::filesystem::create_directories(out_dir);
  write_file_atomic((out_dir / "sweep.csv").string(), csv());
  write_file_atomic((out_dir / "sweep.json").string(), json().dump(2) + "\n");
}

}  // namespace ballista
