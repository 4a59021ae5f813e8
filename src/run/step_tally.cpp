#include "run/step_tally.hpp"

#include <algorithm>
#include <numeric>

#include "core/error.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

void StepTally::add(const StepLimiter& l) {
  if (l.id < 0) return;
  ++samples;
  if (l.multirate > 0.0) {
    multirate_sum += l.multirate;
    ++multirate_samples;
  }
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
  if (l.margin > 0.0) {
    e.margin_sum += l.margin;
    ++e.margin_samples;
  }
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
  out["max_dt_samples"] = max_dt_samples;
  if (multirate_samples > 0) out["multirate_mean"] = multirate_sum / static_cast<double>(multirate_samples);
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
    if (e.margin_samples > 0) j["margin_mean"] = e.margin_sum / static_cast<double>(e.margin_samples);
    list.push_back(j);
  }
  return out;
}

void StepTally::save(StateArchive& a) const {
  // Per entry: body, viscous, samples, ids_capped, margin_samples, the id count, the ids; and J_min,
  // J_max, signal_max, margin_sum.
  std::vector<std::int64_t> ints{samples, max_dt_samples, static_cast<std::int64_t>(entries.size())};
  std::vector<double> reals;
  for (const Entry& e : entries) {
    ints.insert(ints.end(), {e.body, e.viscous ? 1 : 0, e.samples, e.ids_capped ? 1 : 0, e.margin_samples,
                             static_cast<std::int64_t>(e.ids.size())});
    ints.insert(ints.end(), e.ids.begin(), e.ids.end());
    reals.insert(reals.end(), {e.J_min, e.J_max, e.signal_max, e.margin_sum});
  }
  a.put("run.step_tally.ints", ints);
  a.put("run.step_tally.reals", reals);
  a.put("run.step_tally.multirate_samples", std::vector<std::int64_t>{multirate_samples});
  a.put("run.step_tally.multirate_sum", std::vector<double>{multirate_sum});
}

void StepTally::load(const StateArchive& a) {
  *this = StepTally{};
  if (!a.has("run.step_tally.ints")) return;
  const std::vector<std::int64_t>& v = a.ints("run.step_tally.ints");
  auto bad = [] { return Error("checkpoint: run.step_tally is malformed"); };
  if (v.size() < 3 || v[2] < 0) throw bad();
  const std::size_t n = static_cast<std::size_t>(v[2]);
  const std::vector<double>& r = a.reals("run.step_tally.reals", 4 * n);
  samples = v[0];
  max_dt_samples = v[1];
  std::size_t at = 3;
  for (std::size_t k = 0; k < n; ++k) {
    if (at + 6 > v.size() || v[at + 5] < 0) throw bad();
    Entry e;
    e.body = static_cast<int>(v[at]);
    e.viscous = v[at + 1] != 0;
    e.samples = v[at + 2];
    e.ids_capped = v[at + 3] != 0;
    e.margin_samples = v[at + 4];
    const std::size_t m = static_cast<std::size_t>(v[at + 5]);
    at += 6;
    if (at + m > v.size()) throw bad();
    e.ids.assign(v.begin() + static_cast<std::ptrdiff_t>(at), v.begin() + static_cast<std::ptrdiff_t>(at + m));
    at += m;
    e.J_min = r[4 * k];
    e.J_max = r[4 * k + 1];
    e.signal_max = r[4 * k + 2];
    e.margin_sum = r[4 * k + 3];
    entries.push_back(std::move(e));
  }
  if (at != v.size()) throw bad();
  // A checkpoint written before the multi-rate figure existed has none: the mean is then over the
  // samples taken after the restart.
  if (a.has("run.step_tally.multirate_samples")) {
    multirate_samples = a.ints("run.step_tally.multirate_samples", 1)[0];
    if (multirate_samples < 0) throw bad();
    multirate_sum = a.reals("run.step_tally.multirate_sum", 1)[0];
  }
}

}  // namespace ballista
