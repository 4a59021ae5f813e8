#include "run/run_state.hpp"

namespace ballista {

JsonValue StageRecord::json() const {
  JsonValue rec = JsonValue::object();
  rec["name"] = name;
  rec["start_time"] = start_time;
  rec["end_time"] = end_time;
  rec["ended_by"] = ended_by;
  rec["damping"] = damping;
  if (checked) {
    rec["worst_deviation"] = worst_deviation;
    rec["worst_particle"] = worst_particle;
    rec["fraction_within"] = fraction_within;
  }
  return rec;
}

namespace {
/// Stage names and how they ended, one per line (names are deck keys: no line breaks).
std::string join_lines(const std::vector<StageRecord>& st, bool names) {
  std::string out;
  for (const auto& r : st) out += (names ? r.name : r.ended_by) + "\n";
  return out;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t nl = text.find('\n', at);
    out.push_back(text.substr(at, nl - at));
    at = nl == std::string::npos ? text.size() : nl + 1;
  }
  return out;
}
}  // namespace

void RunState::save(StateArchive& a) const {
  a.put("run.clock", std::vector<double>{stage_start, end, next_output, next_checkpoint, total0, energy_scale,
                                         worst_drift, min_dt, limiter_dt, limiter_time, particle_steps, dt,
                                         wall_before, limiter.wave_speed, limiter.speed, limiter.J});
  a.put("run.counters", std::vector<std::int64_t>{stage, limiter.id, limiter.body});
  std::vector<double> reals;
  std::vector<std::int64_t> ints;
  for (const auto& r : stages) {
    reals.insert(reals.end(), {r.start_time, r.end_time, r.damping, r.worst_deviation, r.fraction_within});
    ints.insert(ints.end(), {r.checked ? 1 : 0, r.worst_particle});
  }
  a.put("run.stage_log.values", reals);
  a.put("run.stage_log.flags", ints);
  a.put_text("run.stage_log.names", join_lines(stages, true));
  a.put_text("run.stage_log.ended_by", join_lines(stages, false));
  std::string lines;
  for (const auto& w : warnings) lines += w + "\n";
  a.put_text("run.warnings", lines);
  a.put("run.limiter_cell", std::vector<double>{limiter.cell, limiter.viscous ? 1.0 : 0.0});
  step_tally.save(a);
}

void RunState::load(const StateArchive& a) {
  a.get_into("run.clock", {&stage_start, &end, &next_output, &next_checkpoint, &total0, &energy_scale, &worst_drift,
                           &min_dt, &limiter_dt, &limiter_time, &particle_steps, &dt, &wall_before, &limiter.wave_speed,
                           &limiter.speed, &limiter.J});
  a.get_integers_into("run.counters", stage, limiter.id, limiter.body);
  if (a.has("run.limiter_cell")) {  // absent from checkpoints written before it was kept
    const auto& lc = a.reals("run.limiter_cell", 2);
    limiter.cell = lc[0];
    limiter.viscous = lc[1] != 0.0;
  }
  step_tally.load(a);
  const std::vector<std::string> names = split_lines(a.text("run.stage_log.names"));
  const std::vector<std::string> how = split_lines(a.text("run.stage_log.ended_by"));
  const auto& v = a.reals("run.stage_log.values", 5 * names.size());
  const auto& f = a.ints("run.stage_log.flags", 2 * names.size());
  stages.clear();
  for (std::size_t k = 0; k < names.size(); ++k) {
    StageRecord r;
    r.name = names[k];
    r.ended_by = k < how.size() ? how[k] : std::string();
    r.start_time = v[5 * k];
    r.end_time = v[5 * k + 1];
    r.damping = v[5 * k + 2];
    r.worst_deviation = v[5 * k + 3];
    r.fraction_within = v[5 * k + 4];
    r.checked = f[2 * k] != 0;
    r.worst_particle = f[2 * k + 1];
    stages.push_back(r);
  }
  // Checkpoints written before the warnings were kept have none.
  warnings = a.has("run.warnings") ? split_lines(a.text("run.warnings")) : std::vector<std::string>{};
}

}  // namespace ballista
