// summary.json at the end of a run (completed, failed or interrupted): status, probes, stages,
// the penetration analysis, the solver's results and tables, statistics and the energy audit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "analysis/penetration_probe.hpp"
#include "core/build_info.hpp"
#include "core/energy_terms.hpp"
#include "core/host_cpu.hpp"
#include "core/parallel.hpp"
#include "core/warning_log.hpp"
#include "io/summary_units.hpp"
#include "io/summary_writer.hpp"
#include "points/point_exchange.hpp"
#include "points/probe_registry.hpp"
#include "run/fragment_summary.hpp"
#include "run/headlines.hpp"
#include "run/run_loop.hpp"

namespace ballista {

namespace {

/// summary.json "statistics": the run's size and speed and its smallest step with the point that
/// set it.
void write_statistics(JsonValue& st, const Scenario& sc, const RunState& rs, const RunResult& result,
                      std::int64_t particles, std::int64_t seeded, std::int64_t deleted, double particle_steps,
                      const char* solver, int ranks) {
  st = JsonValue::object();
  st["solver"] = solver;
  st["steps"] = result.steps;
  st["end_time"] = result.time;
  st["wall_time"] = result.wall_seconds;
  st["threads"] = max_threads();
  st["cpu"] = host_cpu();
  st["ranks"] = ranks;
  st["particles"] = particles;  // active at the end
  st["particles_seeded"] = seeded;
  st["particles_deleted"] = deleted;
  st["particle_steps"] = particle_steps;
  st["particle_steps_per_second"] = result.particle_steps_per_second;
  st["min_dt"] = std::isfinite(rs.min_dt) ? rs.min_dt : 0.0;
  st["worst_energy_drift"] = rs.worst_drift;
  if (rs.step_tally.samples > 0 || rs.step_tally.max_dt_samples > 0) st["step_set_by"] = rs.step_tally.json(sc);
  const StepLimiter& limiter = rs.limiter;
  if (limiter.id < 0) return;
  JsonValue& lim = st["min_dt_set_by"];
  lim = JsonValue::object();
  lim["particle"] = limiter.id;
  lim["body"] =
      limiter.body >= 0 && limiter.body < static_cast<int>(sc.bodies.size()) ? sc.bodies[limiter.body].name : "";
  lim["time"] = rs.limiter_time;
  lim["dt"] = rs.limiter_dt;
  lim["wave_speed"] = limiter.wave_speed;
  lim["speed"] = limiter.speed;
  lim["J"] = limiter.J;
  if (limiter.cell > 0.0) lim["cell"] = limiter.cell;
  lim["signal"] = limiter.viscous ? "bulk_viscosity" : "wave";
}

/// summary.json "energy": every term of the audit, the balance's reference and its residual.
void write_energy(JsonValue& en, const EnergyTotals& e, double total0, double scale) {
  en = JsonValue::object();
  en["initial_total"] = total0;
  for (const EnergyTerm& t : kEnergyTerms)
    if (t.summary_key) en[t.summary_key] = t.value(e, 0.0);
  en["scale"] = scale;
  en["residual"] = e.total() - total0;
  en["residual_over_scale"] = scale > 0 ? (e.total() - total0) / scale : 0.0;
}

}  // namespace

/// The unit of each probe's value: its kind's, or for a field's maximum the field's.
std::map<std::string, std::string> RunLoop::probe_units() const {
  std::map<std::string, std::string> units;
  const FieldStore& pts = solver_->points();
  for (const ProbeSpec& p : sc_.probes) {
    const ProbeFactory* f = find_probe(p.type);
    std::string unit = f ? f->unit : "";
    if (unit.empty())
      if (const auto it = p.params.choices.find("field"); it != p.params.choices.end() && pts.has(it->second))
        unit = pts.info(it->second).unit;
    if (!unit.empty()) units[p.name] = unit;
  }
  return units;
}

/// The run's warnings: those restored from the checkpoint it continues, then this process's, each
/// once (a restart logs again what its set-up logged before, e.g. an under-resolved penetrator).
std::vector<std::string> RunLoop::run_warnings() const {
  std::vector<std::string> all = rs_.warnings;
  for (std::string& w : warnings_since(warning_mark_))
    if (std::find(all.begin(), all.end(), w) == all.end()) all.push_back(std::move(w));
  return all;
}

/// Fills the result's totals and writes summary.json (rank 0). A non-finite number in it fails
/// the run: it is garbage, never a success.
void RunLoop::write_summary(double wall) {
  namespace fs = std::filesystem;
  const double particle_steps = comm_.sum(rs_.particle_steps);  // over every rank
  const EnergyTotals e = solver_->energies();
  result_.steps = solver_->steps();
  result_.time = solver_->time();
  result_.wall_seconds = wall;
  result_.particle_steps_per_second = wall > 0 ? particle_steps / wall : 0.0;
  const std::vector<double> pv = probe_values(e);
  SummaryWriter summary;
  summary["status"] = result_.ok ? "completed" : result_.interrupted ? "interrupted" : "failed";
  if (!result_.ok) {
    summary["error"] = result_.error;
    if (!result_.interrupted) summary["failed_step"] = result_.failed_step;
    if (result_.failed_particle >= 0) summary["failed_particle"] = result_.failed_particle;
  }
  if (!sc_.output.track.empty()) summary["tracked_particles"] = sc_.output.track;
  summary["deck"] = restart_ ? restart_->text("run.deck_file") : sc_.file;
  if (restart_) summary["restarted_from"] = opt_.restart_from;
  // What made these numbers: the version and the commit built (core/build_info.hpp).
  JsonValue& build = summary["build"];
  build = JsonValue::object();
  build["version"] = BALLISTA_VERSION;
  build["commit"] = build_commit();
  build["cpu_target"] = build_cpu_target();
  JsonValue& probes = summary["probes"];
  probes = JsonValue::object();
  for (size_t k = 0; k < sc_.probes.size(); ++k) {
    probes[sc_.probes[k].name] = pv[k];
    result_.probes.emplace_back(sc_.probes[k].name, pv[k]);
  }
  if (nstages_ > 0) {
    JsonValue stage_log = JsonValue::array();
    for (const auto& r : rs_.stages) stage_log.push_back(r.json());
    summary["stages"] = stage_log;
    summary["main_stage_start"] = rs_.stage == nstages_ ? JsonValue(rs_.stage_start) : JsonValue();
  }
  if (penetration_) {
    try {
      const FieldStore all = comm_.distributed() ? gather_points(comm_, solver_->points()) : FieldStore{};
      if (root_)
        penetration_->finish(comm_.distributed() ? all : solver_->points(), opt_.out_dir, sc_.simulation.end_time,
                             summary["penetration"]);
    } catch (const std::exception& w) {
      spdlog::error("penetration analysis failed: {}", w.what());
    }
  }
  if (!tension_.empty()) summary["tension"] = tension_.summary();
  // What the discretisation itself reports (peridynamics: fragments and broken bonds).
  try {
    if (const auto values = solver_->result_values(); !values.empty()) {
      JsonValue& sr = summary["solver_results"];
      sr = JsonValue::object();
      for (const auto& [k, v] : values) sr[k] = v;
    }
    if (const auto timing = solver_->timing_values(); !timing.empty()) {
      JsonValue& tm = summary["timing"];
      tm = JsonValue::object();
      for (const auto& [k, v] : timing) tm[k + "_seconds"] = v;
    }
    const std::vector<ResultTable> tables = root_ ? solver_->result_tables() : std::vector<ResultTable>{};
    for (const ResultTable& t : tables) {
      HistoryWriter csv((fs::path(opt_.out_dir) / (t.name + ".csv")).string(), t.columns);
      for (const auto& row : t.rows) csv.row(row);
    }
    // No figure when interrupted: mpirun SIGKILLs the ranks odls_base_sigkill_timeout (1 s by
    // default) after it passed SIGTERM on, too soon for matplotlib; the restarted run draws it.
    report_fragments(tables, opt_.out_dir, opt_.plots && !result_.interrupted, summary.root(),
                     sc_.output.fragment_min_mass);
  } catch (const std::exception& w) {
    spdlog::error("the solver's results could not be written: {}", w.what());
  }
  std::int64_t deleted_points = 0;
  for (double n : e.removed_points_by_body) deleted_points += static_cast<std::int64_t>(n);
  write_statistics(summary["statistics"], sc_, rs_, result_,
                   comm_.sum(static_cast<std::int64_t>(solver_->points().size())), seeded_, deleted_points,
                   particle_steps, solver_->name(), comm_.size());
  if (deleted_points > 0) summary["deleted"] = deletions_->summary(e);
  for (const auto& w : deletions_->probe_warnings(e)) spdlog::warn("{}", w);
  // Every warning of this run, these included (core/warning_log.hpp).
  if (const auto warnings = run_warnings(); !warnings.empty()) {
    JsonValue& list = summary["warnings"];
    list = JsonValue::array();
    const std::size_t shown = std::min<std::size_t>(warnings.size(), 50);  // the console log has them all
    for (std::size_t k = 0; k < shown; ++k) list.push_back(warnings[k]);
    if (warnings.size() > shown) list.push_back(fmt::format("... and {} more warnings", warnings.size() - shown));
  }
  write_energy(summary["energy"], e, rs_.total0, rs_.energy_scale);
  const std::vector<std::string> bad = non_finite_numbers(summary.root());
  if (!bad.empty() && result_.ok) {
    std::string list;
    for (size_t k = 0; k < bad.size() && k < 8; ++k) list += (k ? "; " : "") + bad[k];
    if (bad.size() > 8) list += fmt::format("; and {} more", bad.size() - 8);
    result_.ok = false;
    result_.error = "non-finite results at the end of the run: " + list +
                    " (a probe that selects no particle, or a value that overflowed; see the deck's probes)";
    spdlog::error("run failed: {}", result_.error);
    summary["status"] = "failed";
    summary["error"] = result_.error;
  }
  summary["units"] = summary_units(summary.root(), probe_units());
  if (root_) {
    result_.headlines = headline_lines(summary.root());
    summary.write((fs::path(opt_.out_dir) / "summary.json").string());
  }
}

}  // namespace ballista
