#include "run/deletion_report.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace ballista {

namespace {

double share(const EnergyTotals& e, std::size_t b) {
  return e.seeded_mass_by_body[b] > 0.0 ? e.removed_mass_by_body[b] / e.seeded_mass_by_body[b] : 0.0;
}

}  // namespace

DeletionReport::DeletionReport(const Scenario& sc, const EnergyTotals& start)
    : sc_(sc),
      reported_(start.removed_points_by_body),
      rows_(sc.bodies.size(), 0),
      decile_(sc.bodies.size(), 0) {
  reported_.resize(sc.bodies.size(), 0.0);
  for (std::size_t b = 0; b < decile_.size() && b < start.seeded_mass_by_body.size(); ++b)
    decile_[b] = static_cast<int>(std::floor(10.0 * share(start, b)));
}

void DeletionReport::update(const EnergyTotals& e, long step, double time) {
  for (std::size_t b = 0; b < reported_.size() && b < e.removed_points_by_body.size(); ++b) {
    const double now = e.removed_points_by_body[b];
    if (!(now > reported_[b])) continue;
    const double fresh = now - reported_[b];
    reported_[b] = now;
    const double f = share(e, b);
    const int decile = static_cast<int>(std::floor(10.0 * f));
    const bool log = rows_[b] == 0 || decile > decile_[b];
    decile_[b] = std::max(decile_[b], decile);
    if (!log) continue;
    ++rows_[b];
    spdlog::warn("step {} (t = {:.6g} s): {:g} points of body '{}' left the grid and were deleted; {:g} so far, {:.4g} "
                 "kg ({:.3g} % of its mass) and {:.4g} J carried off{}",
                 step, time, fresh, sc_.bodies[b].name, now, e.removed_mass_by_body[b], 100.0 * f,
                 e.removed_energy_by_body[b],
                 rows_[b] == 1 ? " (logged again at each 10 % of its mass; summary.json lists them all)" : "");
  }
}

JsonValue DeletionReport::summary(const EnergyTotals& e) const {
  JsonValue out = JsonValue::object();
  for (std::size_t b = 0; b < e.removed_points_by_body.size() && b < sc_.bodies.size(); ++b) {
    if (!(e.removed_points_by_body[b] > 0.0)) continue;
    JsonValue& j = out[sc_.bodies[b].name];
    j["points"] = static_cast<std::int64_t>(e.removed_points_by_body[b]);
    j["mass"] = e.removed_mass_by_body[b];
    j["energy"] = e.removed_energy_by_body[b];
    j["mass_fraction"] = share(e, b);
  }
  return out;
}

std::vector<std::string> DeletionReport::probe_warnings(const EnergyTotals& e) const {
  std::vector<std::string> out;
  for (const ProbeSpec& pr : sc_.probes) {
    const auto it = pr.params.choices.find("body");
    if (it == pr.params.choices.end()) continue;
    const int b = body_index(sc_, it->second);
    if (b < 0 || static_cast<std::size_t>(b) >= e.removed_points_by_body.size()) continue;
    const double f = share(e, static_cast<std::size_t>(b));
    if (f > 0.5)
      out.push_back(fmt::format("probe '{}' measures body '{}', which has lost {:.3g} % of its mass to deletion "
                                "({:g} points left the grid): its value describes what is left",
                                pr.name, it->second, 100.0 * f, e.removed_points_by_body[b]));
  }
  return out;
}

}  // namespace ballista
