#include "run/fragment_summary.hpp"

#include <algorithm>
#include <cmath>

#include <spdlog/spdlog.h>

#include "analysis/mott_fit.hpp"
#include "core/error.hpp"
#include "run/fragment_plots.hpp"

namespace ballista {

namespace {

/// Index of `name` in the table's columns, -1 if absent.
int column(const ResultTable& t, const std::string& name) {
  const auto it = std::find(t.columns.begin(), t.columns.end(), name);
  return it == t.columns.end() ? -1 : static_cast<int>(it - t.columns.begin());
}

/// count, largest, means, total and the Mott fit of `masses` into `j`.
void mass_statistics(const std::vector<double>& masses, JsonValue& j) {
  double total = 0.0, largest = 0.0, square = 0.0;
  for (double m : masses) total += m, largest = std::max(largest, m), square += m * m;
  // A value that does not exist is left out (never null: the fuzz harness and readers treat a null
  // number as garbage), and mott_reason says why the fit is missing.
  j["count"] = static_cast<std::int64_t>(masses.size());
  j["largest_mass"] = largest;
  if (!masses.empty()) j["mean_mass"] = total / static_cast<double>(masses.size());
  // The mass of the fragment an average unit of mass ends up in: insensitive to the many loose
  // points of a fine lattice, which set mean_mass (a point's mass is the lattice's).
  if (total > 0.0) j["mass_weighted_mean_mass"] = square / total;
  j["total_mass"] = total;
  const MottFit f = fit_mott(masses);
  if (f.ok) {
    j["mott_N0"] = f.N0;
    j["mott_mu"] = f.mu;
    if (std::isfinite(f.r2)) j["mott_r2"] = f.r2;  // no line through equal masses
  } else {
    j["mott_reason"] = f.reason;
  }
}

}  // namespace

JsonValue fragment_summary(const ResultTable& table, double min_mass) {
  const int im = column(table, "mass"), it = column(table, "time");
  if (im < 0) throw Error("table '" + table.name + "' has no column 'mass'");
  // The last snapshot: the rows at the time of the last row (rows are grouped by ascending time);
  // without a time column every row.
  const double t_last = it >= 0 && !table.rows.empty() ? table.rows.back().at(it) : 0.0;
  std::vector<double> masses;
  for (const auto& row : table.rows)
    if (it < 0 || row.at(it) == t_last) masses.push_back(row.at(im));
  JsonValue j = JsonValue::object();
  if (it >= 0 && !table.rows.empty()) j["time"] = t_last;
  mass_statistics(masses, j);
  if (min_mass > 0.0) {
    std::vector<double> heavy;
    for (double m : masses)
      if (m >= min_mass) heavy.push_back(m);
    JsonValue& a = j["above_min_mass"];
    a["min_mass"] = min_mass;
    mass_statistics(heavy, a);
  }
  return j;
}

void report_fragments(const std::vector<ResultTable>& tables, const std::string& out_dir, bool plots,
                      JsonValue& summary, double min_mass) {
  const auto t = std::find_if(tables.begin(), tables.end(), [](const ResultTable& r) { return r.name == "fragments"; });
  if (t == tables.end()) return;
  try {
    summary["fragments"] = fragment_summary(*t, min_mass);
  } catch (const std::exception& e) {
    spdlog::warn("no fragment statistics in summary.json: {}", e.what());
  }
  if (!plots) return;
  try {
    if (const std::string err = make_fragment_plots(out_dir); !err.empty())
      spdlog::warn("no fragment figures: {} (--no-plots skips them)", err);
  } catch (const std::exception& e) {
    spdlog::warn("no fragment figures: {} (--no-plots skips them)", e.what());
  }
}

}  // namespace ballista
