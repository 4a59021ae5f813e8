#include "run/step_tally.hpp"

#include <algorithm>
#include <numeric>

#include "scenario/scenario.hpp"

namespace ballista {

void StepTally::add(const StepLimiter& l) {
  if (l.id < 0) return;
  ++samples;
  auto it = std::find_if(entries.begin(), entries.end(),
                         [&](const Entry& e) { return e.body == l.body && e.viscous == l.viscous; });
  if (it == entries.end()) {
    Entry e;
    e.body = l.body;
    e.viscous = l.viscous;
    e.J_min = e.J_max = l.J;
    entries.push_back(e);
    it = entries.end() - 1;
  }
  Entry& e = *it;
  ++e.samples;
  e.J_min = std::min(e.J_min, l.J);
  e.J_max = std::max(e.J_max, l.J);
  e.signal_max = std::max(e.signal_max, l.wave_speed);
  const auto at = std::lower_bound(e.ids.begin(), e.ids.end(), l.id);
  if (at != e.ids.end() && *at == l.id) return;
  if (e.ids.size() < kStepTallyMaxIds)
    e.ids.insert(at, l.id);
  else
    e.ids_capped = true;
}

JsonValue StepTally::json(const Scenario& sc) const {
  JsonValue out = JsonValue::object();
  out["sample_interval"] = kStepTallyInterval;
  out["samples"] = samples;
  JsonValue& list = out["entries"];
  list = JsonValue::array();
  // Most samples first; ties keep the order of first appearance.
  std::vector<std::size_t> order(entries.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return entries[a].samples > entries[b].samples; });
  for (std::size_t k : order) {
    const Entry& e = entries[k];
    JsonValue j = JsonValue::object();
    j["body"] = e.body >= 0 && e.body < static_cast<int>(sc.bodies.size()) ? sc.bodies[e.body].name : "";
    j["signal"] = e.viscous ? "bulk_viscosity" : "wave";
    j["share"] = samples > 0 ? static_cast<double>(e.samples) / static_cast<double>(samples) : 0.0;
    j["samples"] = e.samples;
    j["points"] = static_cast<std::int64_t>(e.ids.size());
    j["points_at_least"] = e.ids_capped;
    j["J_min"] = e.J_min;
    j["J_max"] = e.J_max;
    j["signal_speed_max"] = e.signal_max;
    list.push_back(j);
  }
  return out;
}

void StepTally::save(StateArchive& a) const {
  // Per entry: body, viscous, samples, ids_capped, the id count, the ids; and J_min, J_max, signal_max.
  std::vector<std::int64_t> ints{samples, static_cast<std::int64_t>(entries.size())};
  std::vector<double> reals;
  for (const Entry& e : entries) {
    ints.insert(ints.end(), {e.body, e.viscous ? 1 : 0, e.samples, e.ids_capped ? 1 : 0,
                             static_cast<std::int64_t>(e.ids.size())});
    ints.insert(ints.end(), e.ids.begin(), e.ids.end());
    reals.insert(reals.end(), {e.J_min, e.J_max, e.signal_max});
  }
  a.put("run.step_tally.ints", ints);
  a.put("run.step_tally.reals", reals);
}

void StepTally::load(const StateArchive& a) {
  *this = StepTally{};
  if (!a.has("run.step_tally.ints")) return;
  const std::vector<std::int64_t>& v = a.ints("run.step_tally.ints");
  const std::size_t n = static_cast<std::size_t>(v.at(1));
  const std::vector<double>& r = a.reals("run.step_tally.reals", 3 * n);
  samples = v.at(0);
  std::size_t at = 2;
  for (std::size_t k = 0; k < n; ++k) {
    Entry e;
    e.body = static_cast<int>(v.at(at));
    e.viscous = v.at(at + 1) != 0;
    e.samples = v.at(at + 2);
    e.ids_capped = v.at(at + 3) != 0;
    const std::size_t m = static_cast<std::size_t>(v.at(at + 4));
    at += 5;
    e.ids.assign(v.begin() + static_cast<std::ptrdiff_t>(at), v.begin() + static_cast<std::ptrdiff_t>(at + m));
    at += m;
    e.J_min = r[3 * k];
    e.J_max = r[3 * k + 1];
    e.signal_max = r[3 * k + 2];
    entries.push_back(std::move(e));
  }
}

}  // namespace ballista
