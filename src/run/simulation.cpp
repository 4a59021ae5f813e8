#include "run/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "analysis/penetration_probe.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint_file.hpp"
#include "io/deck_changes.hpp"
#include "io/history_writer.hpp"
#include "io/particle_writer.hpp"
#include "io/run_folder.hpp"
#include "io/summary_writer.hpp"
#include "points/point_exchange.hpp"
#include "points/probe_registry.hpp"
#include "points/solver_registry.hpp"
#include "run/fragment_summary.hpp"
#include "run/particle_tracker.hpp"
#include "run/deletion_report.hpp"
#include "run/interrupt.hpp"
#include "run/progress.hpp"
#include "run/run_state.hpp"
#include "run/stage_criterion.hpp"

namespace ballista {

std::vector<std::unique_ptr<Material>> make_materials(const Scenario& sc) {
  std::vector<std::unique_ptr<Material>> out;
  for (const auto& m : sc.materials) {
    const MaterialFactory* f = find_material(m.model);
    if (!f)
      throw DeckError(m.mark.file, m.mark.line, m.mark.column, m.mark.key_path + ".model",
                      "unknown material model '" + m.model + "'");
    out.push_back(f->create(m.name, m.params));
  }
  return out;
}

namespace {
/// Several ranks: a solver that does not run distributed is refused (run_simulation asks before
/// anything is written, make_solver again for its other callers).
void check_distributed(const Scenario& sc, const SolverFactory& f, const Communicator& comm) {
  if (comm.distributed() && !f.distributed)
    throw DeckError(sc.file, 0, 0, "simulation.solver",
                    "solver '" + sc.simulation.solver + "' runs on one MPI rank only so far (" +
                        std::to_string(comm.size()) + " ranks were started); run it without mpirun, or with -np 1");
}
}  // namespace

std::unique_ptr<Solver> make_solver(const Scenario& sc, const Communicator& comm) {
  const SolverFactory* f = find_solver(sc.simulation.solver);
  if (!f) {
    std::string names;
    for (const auto& s : solver_registry()) names += (names.empty() ? "" : ", ") + s.name;
    throw Error("unknown solver '" + sc.simulation.solver + "' (registered: " + names + ")");
  }
  check_distributed(sc, *f, comm);
  return f->create(sc, make_materials(sc), comm);
}

namespace {

/// "particle 12 of body 'bar' (wave speed 4000 m/s, speed 200 m/s, J 0.98)".
std::string describe_limiter(const Scenario& sc, const StepLimiter& l) {
  if (l.id < 0) return "no particle";
  const std::string body =
      l.body >= 0 && l.body < static_cast<int>(sc.bodies.size()) ? " of body '" + sc.bodies[l.body].name + "'" : "";
  return fmt::format("particle {}{} (wave speed {:.4g} m/s, speed {:.4g} m/s, J {:.4g})", l.id, body, l.wave_speed,
                     l.speed, l.J);
}

/// Refuses a run whose estimated step count (simulated time / first stable step) exceeds
/// simulation.step_limit (issue 11: cfl 1e-12 or max_dt 1e-300 gave an ETA of 1e11 s).
void check_step_estimate(const Scenario& sc, Solver& solver) {
  double span = sc.simulation.end_time;  // simulated time: the main stage plus the longest stages
  for (const StageSpec& st : sc.stages) span += st.until.empty() ? st.duration : st.max_duration;
  const double dt = solver.stable_dt();
  if (!(dt > 0.0) || !std::isfinite(dt)) return;  // the loop's own check reports it with its step
  const double steps = span / dt;
  if (steps <= static_cast<double>(sc.simulation.step_limit)) return;
  throw DeckError(sc.file, 0, 0, "simulation.step_limit",
                  fmt::format("the run would take about {:.3g} steps ({:.6g} s of simulated time at a stable step of "
                              "{:.3g} s, set by {}; cfl {:g}, max_dt {:g} s), more than simulation.step_limit = {}; "
                              "check cfl, max_dt, the moduli and the cell size, or raise simulation.step_limit to "
                              "insist",
                              steps, span, dt, describe_limiter(sc, solver.step_limiter()), sc.simulation.cfl,
                              sc.simulation.max_dt, sc.simulation.step_limit));
}

/// Output fields: the deck's list (validated against the points) or all.
std::vector<std::string> output_fields(const Scenario& sc, const FieldStore& points) {
  for (const auto& f : sc.output.fields)
    if (!points.has(f)) {
      std::string names;
      for (const auto& fi : points.fields()) names += (names.empty() ? "" : ", ") + fi.name;
      throw DeckError(sc.file, 0, 0, "output.fields", "unknown field '" + f + "' (available: " + names + ")");
    }
  return sc.output.fields;
}

/// What a restart may not change: the solver, the grid, the bodies' materials and seeding, the
/// materials' models (--set may change the end, outputs and guards; docs/restart.md).
std::string layout_signature(const Scenario& sc) {
  std::string s = "solver " + sc.simulation.solver + "\ngrid " +
                  fmt::format("{} {} {} {} {} {} {}", sc.grid.lower[0], sc.grid.lower[1], sc.grid.lower[2],
                              sc.grid.upper[0], sc.grid.upper[1], sc.grid.upper[2], sc.grid.cell_size) +
                  "\n";
  for (const auto& m : sc.materials) s += "material " + m.name + " " + m.model + "\n";
  for (const auto& b : sc.bodies) {
    s += "body " + b.name + " " + b.material + " " + std::to_string(b.particles_per_cell);
    // Only when given: checkpoints written before point_spacing existed keep their signature.
    if (b.point_spacing > 0.0) s += fmt::format(" point_spacing {:.17g}", b.point_spacing);
    s += "\n";
  }
  return s;
}

/// Refuses a restart whose deck seeds other points than the checkpoint's (naming the first
/// differing line).
void check_layout(const StateArchive& a, const Scenario& sc, const std::string& path) {
  if (!a.has("run.layout")) return;
  const std::string want = a.text("run.layout"), have = layout_signature(sc);
  if (want == have) return;
  std::size_t at = 0;
  while (at < want.size() && at < have.size() && want[at] == have[at]) ++at;
  const std::size_t line = want.rfind('\n', at == 0 ? 0 : at - 1);
  const std::size_t from = line == std::string::npos ? 0 : line + 1;
  throw Error("the deck does not match the checkpoint " + path + ": it has '" +
              have.substr(from, have.find('\n', from) - from) + "' where the checkpoint has '" +
              want.substr(from, want.find('\n', from) - from) +
              "' (a restart may change the end time, outputs and guards, not the solver, grid, bodies or material "
              "models)");
}

/// Refuses a restart whose deck (the checkpoint's, with the --set overrides) changes more than the
/// run's end, outputs, checkpoints, limits and guards (docs/restart.md), naming what it changes.
void check_restart_changes(const StateArchive& a, const Scenario& sc, const std::string& path) {
  std::vector<DeckChange> refused;
  for (const DeckChange& c : deck_changes(a.text("run.deck"), sc.resolved_yaml))
    if (!restart_may_change(c.key_path)) refused.push_back(c);
  if (refused.empty()) return;
  std::string list;
  for (std::size_t k = 0; k < refused.size() && k < 5; ++k)
    list += fmt::format("{}{} ({} -> {})", k ? ", " : "", refused[k].key_path,
                        refused[k].before.empty() ? "not given" : shorten(refused[k].before, 60),
                        refused[k].after.empty() ? "not given" : shorten(refused[k].after, 60));
  if (refused.size() > 5) list += fmt::format(" and {} more", refused.size() - 5);
  throw DeckError(sc.file, 0, 0, refused.front().key_path,
                  "a restart continues the run of checkpoint " + path +
                      " with its physics: it may change the end time, outputs, checkpoints, limits and guards "
                      "(docs/restart.md), but the deck changes " + list +
                      "; run the deck anew to change them");
}

}  // namespace

RunResult run_simulation(const Scenario& sc, const RunOptions& opt) {
  namespace fs = std::filesystem;
  // Every rank runs this loop; rank 0 alone writes files (docs/parallel.md).
  const Communicator comm = Communicator::world();
  const bool root = comm.rank() == 0;
  if (const SolverFactory* f = find_solver(sc.simulation.solver)) check_distributed(sc, *f, comm);
  // Rank 0 holds the results folder for the run (io/run_folder.hpp): another run into it is
  // refused, and a new run removes exactly the files of the previous one. A restart continues
  // the folder it was written in: nothing there is cleared.
  std::optional<RunFolder> folder;
  if (root && !opt.folder_held)
    folder.emplace(opt.out_dir, opt.restart_from.empty() ? RunFolder::Mode::NewRun : RunFolder::Mode::Continue,
                   opt.overwrite);
  std::optional<StateArchive> restart;
  if (!opt.restart_from.empty()) {
    restart = read_checkpoint_file(opt.restart_from);  // every rank reads it
    check_restart_changes(*restart, sc, opt.restart_from);
    check_layout(*restart, sc, opt.restart_from);
    // Checkpoints newer than the one restarted from belong to the abandoned continuation.
    if (root)
      if (const int n = remove_checkpoints_after(opt.out_dir, opt.restart_from))
        spdlog::info("removed {} checkpoints newer than {}", n, opt.restart_from);
  } else if (root) {
    if (folder && folder->removed() > 0)
      spdlog::info("removed {} output files of an earlier run from {}", folder->removed(), opt.out_dir);
    write_file_atomic((fs::path(opt.out_dir) / "resolved.yaml").string(), sc.resolved_yaml);
  }
  clear_interrupt();
  request_threads(opt.threads > 0 ? opt.threads : sc.simulation.threads,  // clamped to the cores present
                  opt.threads > 0 ? "--threads" : "simulation.threads");

  std::unique_ptr<Solver> solver = make_solver(sc, comm);
  // Constants the solver derived from the deck (peridynamic bond constants), echoed as comments.
  // A restart writes the deck it continues with (its end time, outputs and guards may differ).
  if (const std::string derived = solver->derived_constants(); root && (restart || !derived.empty()))
    write_file_atomic((fs::path(opt.out_dir) / "resolved.yaml").string(), sc.resolved_yaml + derived);
  FieldStore& pts = solver->points();
  const std::vector<std::unique_ptr<Probe>> run_probes = make_probes(sc);
  for (const auto& probe : run_probes) probe->check(pts);
  const Dimension dim = sc.simulation.dimension;
  ParticleWriter writer(opt.out_dir, output_fields(sc, pts), sc.output.domains,
                        dim == Dimension::ThreeD ? 3 : 2);
  // A particle file of the current state; several ranks write it together (parallel HDF5, each
  // rank its particles in rank order; io/particle_writer.hpp): collective.
  writer.set_communicator(comm);
  auto write_output = [&] {
    writer.write(solver->time(), solver->steps(), solver->points(), solver->output_nodes());
  };

  std::vector<std::string> columns = {"time", "step", "dt", "kinetic_energy", "internal_energy",
                                      "plastic_work", "external_work", "total_energy", "energy_drift",
                                      "mass", "momentum_x", "momentum_y", "momentum_z",
                                      "removed_mass", "removed_energy", "inserted_energy",
                                      "damping_work", "contact_work", "friction_work", "transfer_work",
                                      "eroded_internal_energy", "chemical_energy", "boundary_work", "viscous_work"};
  for (const auto& pr : sc.probes) columns.push_back(pr.name);
  // Stages: the preparation stages of the deck, then the main stage (index nstages).
  const int nstages = static_cast<int>(sc.stages.size());
  if (nstages > 0) columns.push_back("stage");
  const std::vector<std::string> solver_columns = solver->history_columns();
  columns.insert(columns.end(), solver_columns.begin(), solver_columns.end());
  std::unique_ptr<PenetrationProbe> penetration;
  if (sc.penetration.enabled) {
    penetration = std::make_unique<PenetrationProbe>(sc);
    for (const auto& c : penetration->columns()) columns.push_back(c);
  }
  // Columns where nan is a documented "not applicable yet" (docs/penetration.md), not garbage.
  std::vector<bool> nan_allowed(columns.size(), false);
  for (const std::string& c : PenetrationProbe::nan_when_not_applicable())
    for (size_t k = 0; k < columns.size(); ++k)
      if (penetration && columns[k] == c) nan_allowed[k] = true;
  const std::string history_path = (fs::path(opt.out_dir) / "history.csv").string();
  std::unique_ptr<HistoryWriter> history;  // rank 0's
  if (root)
    history = restart ? std::make_unique<HistoryWriter>(history_path, columns, restart->integer("run.history_bytes"))
                      : std::make_unique<HistoryWriter>(history_path, columns);
  // Particle ids run 0 .. seeded - 1 over every body, active or waiting for activation.
  const std::int64_t seeded = comm.sum(static_cast<std::int64_t>(pts.size() + solver->pending_points()));
  ParticleTracker tracker(sc, opt.out_dir, seeded);
  // The tracked particles as the tracker sees them: several ranks send theirs to rank 0, which
  // alone records (collective; every rank calls it).
  const std::set<std::int64_t> tracked_ids(sc.output.track.begin(), sc.output.track.end());
  auto record_tracks = [&](bool failure) {
    if (tracker.empty()) return;
    if (!comm.distributed()) {
      failure ? tracker.record_failure(solver->points(), solver->time())
              : tracker.record(solver->points(), solver->time(), solver->steps());
      return;
    }
    const FieldStore& local = solver->points();
    const std::int64_t* id = local.ints("id");
    std::vector<Index> mine;
    for (Index p = 0; p < local.size(); ++p)
      if (tracked_ids.count(id[p])) mine.push_back(p);
    FieldStore sub = local.empty_like();
    sub.append_from(local, mine);
    const FieldStore all = gather_points(comm, sub);
    if (!root) return;
    failure ? tracker.record_failure(all, solver->time()) : tracker.record(all, solver->time(), solver->steps());
  };

  if (!restart) check_step_estimate(sc, *solver);

  RunState rs;
  const double interval = sc.output.interval > 0 ? sc.output.interval : sc.simulation.end_time;
  const bool checkpointing = sc.output.checkpoint_interval > 0 || opt.checkpoint_minutes > 0;
  if (restart) {
    solver->load_state(*restart);
    rs.load(*restart);
    if (!root) rs.particle_steps = 0.0;  // the checkpoint holds the total (counted once, on rank 0)
    ParticleWriter::State ws;
    ws.count = static_cast<int>(restart->integer("run.outputs"));
    ws.xdmf_body = restart->text("run.xdmf");
    writer.restore(ws);  // removes the particle files written after the checkpoint (rank 0)
    if (penetration) penetration->load_state(*restart);
    if (!tracker.empty()) {  // rank 0's: it alone writes the tracks
      if (!restart->has("tracks.open"))
        throw Error("the checkpoint was written without output.track.ids; tracks cannot start in the middle of a "
                    "run (their F-tables would miss the steps before): run the deck from the start to track");
      if (root) tracker.load_state(*restart);
    }
    // The deck may have changed the end (--set simulation.end_time=...): the main stage ends
    // end_time after it began; the output clock stays where it was, within the new end.
    if (rs.stage == nstages) {
      rs.end = (nstages > 0 ? rs.stage_start : 0.0) + sc.simulation.end_time;
      if (rs.end < solver->time() * (1.0 - 1e-12))
        throw DeckError(sc.file, 0, 0, "simulation.end_time",
                        fmt::format("simulation.end_time = {:g} s ends the run at t = {:.6g} s, before the checkpoint's "
                                    "t = {:.6g} s: nothing is left to run; give a later end time",
                                    sc.simulation.end_time, rs.end, solver->time()));
      rs.next_output = std::min(rs.next_output, rs.end);
      if (rs.next_output <= solver->time()) rs.next_output = std::min(rs.end, solver->time() + interval);
    }
    if (sc.output.checkpoint_interval <= 0)
      rs.next_checkpoint = RunState::kInf;
    else if (!std::isfinite(rs.next_checkpoint))
      rs.next_checkpoint = solver->time() + sc.output.checkpoint_interval;
    spdlog::info("restarted from {} at step {}, t = {:.6g} s", opt.restart_from, solver->steps(), solver->time());
  } else {
    const EnergyTotals e0 = solver->energies();
    rs.total0 = e0.total();
    // The end time and output times are known once the main stage starts (stage_start + end_time).
    rs.end = nstages > 0 ? RunState::kInf : sc.simulation.end_time;
    rs.next_output = nstages > 0 ? rs.end : interval;
    rs.next_checkpoint = sc.output.checkpoint_interval > 0 ? sc.output.checkpoint_interval : RunState::kInf;
  }
  const double total0 = rs.total0;
  // The scale of the energy residual: kinetic + |internal| + |work of the loads and of damping|.
  // Explosives add the chemical energy released so far (the energy their products work with).
  auto scale_of = [](const EnergyTotals& e) {
    return std::abs(e.kinetic) + std::abs(e.internal) + std::abs(e.external) + std::abs(e.damping) +
           std::abs(e.chemical);
  };
  if (!restart) rs.energy_scale = scale_of(solver->energies());
  DeletionReport deletions(sc, solver->energies());

  auto probe_values = [&](const EnergyTotals& e) {
    const ProbeContext ctx{solver->points(), e, dim, comm};
    std::vector<double> v;
    for (const auto& probe : run_probes) v.push_back(probe->value(ctx));
    return v;
  };
  auto drift_of = [&](const EnergyTotals& e) {
    // Energy drift relative to the largest energy scale seen so far (kinetic + |internal| +
    // |external|), so problems that start at rest and are loaded later are measured sensibly.
    rs.energy_scale = std::max(rs.energy_scale, scale_of(e));
    return rs.energy_scale > 0 ? std::abs(e.total() - total0) / rs.energy_scale : 0.0;
  };
  std::string nonfinite_column;  // set by history_row
  auto history_row = [&](double dt) {
    const EnergyTotals e = solver->energies();
    deletions.update(e, solver->steps(), solver->time());
    const double drift = drift_of(e);
    std::vector<double> row = {solver->time(), static_cast<double>(solver->steps()), dt, e.kinetic,
                               e.internal, e.plastic, e.external, e.total(), drift, e.mass,
                               e.momentum[0], e.momentum[1], e.momentum[2], e.removed_mass,
                               e.removed_energy, e.inserted_energy, e.damping, e.contact, e.friction,
                               e.transfer, e.eroded, e.chemical, e.boundary, e.viscous};
    for (double v : probe_values(e)) row.push_back(v);
    if (nstages > 0) row.push_back(rs.stage);
    for (double v : solver->history_values()) row.push_back(v);
    if (penetration) {
      // Several ranks: the analysis runs on rank 0 over every rank's particles (gathered), which
      // alone keeps the series and writes the row.
      const FieldStore all = comm.distributed() ? gather_points(comm, solver->points()) : FieldStore{};
      if (root)
        for (double v : penetration->sample(comm.distributed() ? all : solver->points(), rs.stage == nstages,
                                            solver->time() - rs.stage_start, solver->reporting_scale()))
          row.push_back(v);
    }
    if (history) history->row(row);
    // The first column that overflowed or is not a number (this rank's row: rank 0 alone has the
    // penetration columns); record_history stops the run on it.
    nonfinite_column.clear();
    for (size_t k = 0; k < row.size() && nonfinite_column.empty(); ++k)
      if (std::isinf(row[k]) || (std::isnan(row[k]) && !(k < nan_allowed.size() && nan_allowed[k])))
        nonfinite_column = fmt::format("'{}' = {}", k < columns.size() ? columns[k] : fmt::format("column {}", k + 1), row[k]);
    return drift;
  };
  // A history row, the worst drift so far and the drift guard (simulation.energy_drift_limit).
  auto record_history = [&](double step_dt) {
    const double drift = history_row(step_dt);
    rs.worst_drift = std::max(rs.worst_drift, drift);
    if (sc.simulation.energy_drift_limit > 0 && drift > sc.simulation.energy_drift_limit)
      throw PhysicsError(fmt::format("energy drift {:.6g} exceeds the limit {:.6g} at step {} (t = {:.6g} s): the "
                                     "run is blowing up",
                                     drift, sc.simulation.energy_drift_limit, solver->steps(), solver->time()));
    // A value that overflowed is garbage even when the energies still balance (a probe of a body
    // whose mass overflows, say): the run stops on it instead of ending "ok" with inf in its tables.
    if (comm.any(!nonfinite_column.empty()))
      throw PhysicsError(fmt::format("non-finite value in history.csv at step {} (t = {:.6g} s): {}; a probe that "
                                     "selects no particle, or a value that overflowed (check the deck's magnitudes: "
                                     "densities, velocities, moduli)",
                                     solver->steps(), solver->time(),
                                     nonfinite_column.empty() ? "on rank 0" : nonfinite_column));
  };

  // ---- checkpoints (docs/restart.md) ---------------------------------------------------------
  // What the outputs looked like at a state: the loop state and how far history.csv, the
  // particle files and the penetration series had got.
  struct Marks {
    RunState rs;
    long long history_bytes = 0;
    int outputs = 0;
    std::size_t xdmf_body_end = 0;
    std::size_t penetration_samples = 0;
    ParticleTracker::State tracks;
    std::size_t calls = 0;  ///< solver calls since the newest checkpoint at the mark
  };
  // The solver calls since the newest checkpoint, so that a failing step can be replayed up to
  // the step before it (the run is deterministic): a step (stage < 0) or a stage start.
  struct SolverCall {
    double dt;
    int stage;
    double damping;
  };
  std::vector<SolverCall> calls_since_checkpoint;
  // A restart's own checkpoint is where a failure before its first checkpoint replays from.
  std::string newest_checkpoint = restart ? opt.restart_from : std::string();
  auto marks_now = [&] {
    return Marks{rs, history ? history->bytes() : 0, writer.count(), writer.xdmf_body_end(),
                 penetration ? penetration->samples() : 0, tracker.state(), calls_since_checkpoint.size()};
  };
  auto wall_start = std::chrono::steady_clock::now();
  auto wall_of_last_checkpoint = wall_start;
  auto write_checkpoint = [&](const Marks& m, const char* why) {
    StateArchive a;
    a.put_text("run.deck", sc.resolved_yaml);
    a.put_text("run.deck_file", restart ? restart->text("run.deck_file") : sc.file);
    a.put_text("run.solver", solver->name());
    a.put_text("run.layout", layout_signature(sc));
    a.put_int("run.step", solver->steps());  // checked against the file's name when it is read
    solver->save_state(a);
    RunState saved = m.rs;
    saved.particle_steps = comm.sum(m.rs.particle_steps);  // each rank counts its own: the total
    saved.wall_before = rs.wall_before +
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    saved.save(a);
    a.put_int("run.history_bytes", m.history_bytes);
    const ParticleWriter::State ws = writer.state_at(m.outputs, m.xdmf_body_end);
    a.put_int("run.outputs", ws.count);
    a.put_text("run.xdmf", ws.xdmf_body);
    if (penetration) penetration->save_state(a, m.penetration_samples);
    if (!tracker.empty() && root) tracker.save_state(a, m.tracks);
    const std::string path = checkpoint_path(opt.out_dir, solver->steps());
    if (root) {  // several ranks: rank 0's archive holds every rank's state (Solver::save_state)
      write_checkpoint_file(path, a);
      prune_checkpoints(opt.out_dir, sc.output.checkpoint_keep);
    }
    newest_checkpoint = path;
    calls_since_checkpoint.clear();
    wall_of_last_checkpoint = std::chrono::steady_clock::now();
    spdlog::info("checkpoint at step {} (t = {:.6g} s, {}): {}", solver->steps(), solver->time(), why, path);
  };
  // After a step: a checkpoint when the simulated-time or the wall-time interval has passed.
  auto maybe_checkpoint = [&] {
    if (!checkpointing || solver->time() >= rs.end * (1.0 - 1e-12)) return;
    const char* why = nullptr;
    if (sc.output.checkpoint_interval > 0 && solver->time() >= rs.next_checkpoint * (1.0 - 1e-12)) {
      while (rs.next_checkpoint <= solver->time() * (1.0 + 1e-12)) rs.next_checkpoint += sc.output.checkpoint_interval;
      why = "output.checkpoint_interval";
    }
    const double minutes =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_of_last_checkpoint).count() / 60.0;
    // Several ranks: rank 0's clock decides for all (the checkpoint is collective).
    bool wall_due = opt.checkpoint_minutes > 0 && minutes >= opt.checkpoint_minutes;
    if (opt.checkpoint_minutes > 0 && comm.distributed()) comm.broadcast(&wall_due, sizeof wall_due, 0);
    if (wall_due) why = "--checkpoint-every-minutes";
    if (!why) return;
    // A checkpoint that cannot be written (disk full) does not stop the run: the previous ones stay.
    try {
      write_checkpoint(marks_now(), why);
    } catch (const std::exception& e) {
      spdlog::error("could not write a checkpoint at step {}: {} (the run goes on; the newest checkpoint is {})",
                    solver->steps(), e.what(), newest_checkpoint.empty() ? "none" : newest_checkpoint);
    }
  };
  // After a step: the due checkpoint, then a signal's request to stop (run/interrupt.hpp), which
  // checkpoints this step (if not just done) and ends the loop. True: stop.
  bool interrupted = false;
  auto after_step = [&] {
    maybe_checkpoint();
    // Several ranks: a signal reaches the ranks at different steps; they stop together.
    const bool asked = comm.distributed() ? comm.any(interrupt_requested()) : interrupt_requested();
    if (!asked || solver->time() >= rs.end * (1.0 - 1e-12)) return false;
    if (newest_checkpoint != checkpoint_path(opt.out_dir, solver->steps()))
      write_checkpoint(marks_now(), "interrupted by a signal");
    interrupted = true;
    return true;
  };
  auto begin_stage = [&](int stage, double damping) {
    solver->begin_stage(stage, damping);
    calls_since_checkpoint.push_back({0.0, stage, damping});
  };

  RunResult result;
  std::unique_ptr<Progress> progress;
  if (!restart) {
    write_output();
    if (nstages > 0) {
      begin_stage(0, sc.stages[0].damping);
      spdlog::info("stage '{}' begins (damping {} 1/s)", sc.stages[0].name, sc.stages[0].damping);
    }
    history_row(0.0);
    record_tracks(false);
    // The first checkpoint is the initial state: a failing run replays from the newest one.
    if (checkpointing) write_checkpoint(marks_now(), "initial state");
  }
  if (rs.stage == nstages) progress = std::make_unique<Progress>(rs.end, opt.progress && root);
  // Ends the current preparation stage: log it, snapshot the particles, start the next stage.
  auto next_stage = [&](const std::string& how, const EquilibriumCheck* check) {
    const StageSpec& st = sc.stages[rs.stage];
    StageRecord rec;
    rec.name = st.name;
    rec.start_time = rs.stage_start;
    rec.end_time = solver->time();
    rec.ended_by = how;
    rec.damping = st.damping;
    if (check) {
      rec.checked = true;
      rec.worst_deviation = check->worst;
      rec.worst_particle = check->worst_id;
      rec.fraction_within = check->within;
    }
    rs.stages.push_back(rec);
    spdlog::info("stage '{}' ended at t = {:.4g} s ({}){}", st.name, solver->time(), how,
                 check ? ": " + describe_equilibrium(st, *check) : std::string());
    record_history(rs.dt);
    write_output();
    ++rs.stage;
    rs.stage_start = solver->time();
    const double damping = rs.stage < nstages ? sc.stages[rs.stage].damping : sc.simulation.damping;
    begin_stage(rs.stage, damping);
    if (rs.stage < nstages) {
      spdlog::info("stage '{}' begins (damping {} 1/s)", sc.stages[rs.stage].name, damping);
    } else {
      rs.end = rs.stage_start + sc.simulation.end_time;
      rs.next_output = std::min(rs.end, rs.stage_start + interval);
      progress = std::make_unique<Progress>(rs.end, opt.progress && root);
      spdlog::info("main stage begins at t = {:.4g} s (damping {} 1/s), runs to {:.4g} s", rs.stage_start, damping,
                   rs.end);
    }
  };
  Marks good;  // the state at the start of the iteration being taken (a failure's last good state)
  bool physics_failure = false;
  try {
    const InterruptScope signals;  // SIGTERM / SIGINT checkpoint and stop, during the steps only
    // Stop within a relative round-off of the end time instead of taking a sliver step.
    while (solver->time() < rs.end * (1.0 - 1e-12)) {
      if (sc.simulation.max_steps > 0 && solver->steps() >= sc.simulation.max_steps) {
        spdlog::warn("simulation.max_steps = {} reached at t = {:.6g} s of {:.6g} s: the run ends early",
                     sc.simulation.max_steps, solver->time(), rs.end);
        break;
      }
      if (checkpointing) good = marks_now();
      double dt = solver->stable_dt();
      if (!(dt > 0.0) || !std::isfinite(dt))
        throw PhysicsError(fmt::format("time step collapsed (dt = {:.6g} s) at step {}, set by {}", dt, solver->steps(),
                                       describe_limiter(sc, solver->step_limiter())));
      if (solver->steps() >= sc.simulation.step_limit)
        throw PhysicsError(fmt::format(
            "the run reached simulation.step_limit = {} steps at t = {:.6g} s of {:.6g} s (dt = {:.6g} s, set by {}): "
            "the time step has collapsed; raise simulation.step_limit to insist",
            sc.simulation.step_limit, solver->time(), rs.end, dt, describe_limiter(sc, solver->step_limiter())));
      // The smallest stable step is what a collapsing time step shows (thesis ch. 6), not the
      // slivers taken to land on output and end times.
      if (dt < 0.9 * rs.limiter_dt) {
        // A new low of the stable step (by 10 %): remember which point sets it.
        rs.limiter = solver->step_limiter();
        rs.limiter_dt = dt;
        rs.limiter_time = solver->time();
      }
      rs.min_dt = std::min(rs.min_dt, dt);
      // Land exactly on output times, the end time and the end of a fixed-length stage.
      dt = std::min({dt, rs.end - solver->time(), rs.next_output - solver->time()});
      if (rs.stage < nstages) {
        const StageSpec& st = sc.stages[rs.stage];
        const double stage_end = rs.stage_start + (st.until.empty() ? st.duration : st.max_duration);
        dt = std::min(dt, stage_end - solver->time());
      }
      rs.particle_steps += static_cast<double>(solver->points().size());
      solver->step(dt);
      rs.dt = dt;
      if (checkpointing) calls_since_checkpoint.push_back({dt, -1, 0.0});
      record_tracks(false);
      if (rs.stage < nstages) {
        const int stage_before = rs.stage;
        const StageSpec& st = sc.stages[rs.stage];
        const double elapsed = solver->time() - rs.stage_start;
        if (st.until.empty()) {
          if (elapsed >= st.duration * (1.0 - 1e-12)) next_stage("duration", nullptr);
        } else {
          const bool last_chance = elapsed >= st.max_duration * (1.0 - 1e-12);
          if ((elapsed >= st.min_duration && solver->steps() % st.check_every == 0) || last_chance) {
            EquilibriumCheck c;
            if (!comm.distributed()) {
              c = check_stress_equilibrium(st, body_index(sc, st.body), solver->points());
            } else {
              // Over every rank's particles on rank 0; its verdict goes to all (they end the stage
              // together).
              const FieldStore all = gather_points(comm, solver->points());
              if (root) c = check_stress_equilibrium(st, body_index(sc, st.body), all);
              comm.broadcast(&c, sizeof c, 0);
            }
            if (c.satisfied && elapsed >= st.min_duration) {
              next_stage(st.until, &c);
            } else if (last_chance) {
              throw PhysicsError("stage '" + st.name + "' did not reach stress equilibrium within its max_duration of " +
                                 fmt::format("{:.6g}", st.max_duration) + " s (step " + std::to_string(solver->steps()) +
                                 "): " + describe_equilibrium(st, c) +
                                 "; raise max_duration, or tune the damping (thesis seed 000 §5.1: near-critical damping)");
            }
          }
        }
        if (rs.stage == stage_before && solver->steps() % std::max(1, sc.output.history_every) == 0)
          record_history(dt);
        if (after_step()) break;
        continue;
      }
      const bool at_output = solver->time() >= rs.next_output * (1.0 - 1e-12);
      const bool at_end = solver->time() >= rs.end * (1.0 - 1e-12);
      if (solver->steps() % std::max(1, sc.output.history_every) == 0 || at_output || at_end) record_history(dt);
      if (at_output && !at_end) {
        write_output();
        rs.next_output += interval;
        if (rs.next_output > rs.end) rs.next_output = rs.end;
      }
      progress->update(solver->time(), solver->steps(), dt);
      if (after_step()) break;
    }
    if (interrupted) {
      // No final particle file: the checkpoint is where the run continues (ballista run --restart).
      result.ok = false;
      result.interrupted = true;
      result.checkpoint = newest_checkpoint;
      result.error = fmt::format("interrupted by a signal at step {} (t = {:.6g} s); continue with ballista run "
                                 "--restart {}",
                                 solver->steps(), solver->time(), opt.out_dir);
      spdlog::warn("{}", result.error);
    } else {
      write_output();
    }
  } catch (const PhysicsError& err) {
    if (progress) progress->finish();
    result.ok = false;
    result.error = err.what();
    result.failed_step = solver->steps();
    // The only dynamic_cast of the run loop: on the error's type, never on the solver.
    if (const auto* pe = dynamic_cast<const ParticleError*>(&err)) result.failed_particle = pe->id();
    try {
      record_tracks(true);
    } catch (const std::exception& w) {
      spdlog::error("could not record the failing step of the tracked particles: {}", w.what());
    }
    spdlog::error("run stopped: {}", err.what());
    physics_failure = true;
    // The failing state goes to a new output file; earlier outputs stay untouched.
    try {
      write_output();
    } catch (const std::exception& w) {
      spdlog::error("could not write the failing state: {}", w.what());
    }
  }
  if (progress) progress->finish();
  const double wall = rs.wall_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const double particle_steps = comm.sum(rs.particle_steps);  // over every rank
  const double min_dt = rs.min_dt;
  const double worst_drift = rs.worst_drift;
  const double energy_scale = rs.energy_scale;
  const StepLimiter& limiter = rs.limiter;
  const double limiter_dt = rs.limiter_dt, limiter_time = rs.limiter_time;
  const int stage = rs.stage;
  const double stage_start = rs.stage_start;
  JsonValue stage_log = JsonValue::array();
  for (const auto& r : rs.stages) stage_log.push_back(r.json());

  const EnergyTotals e = solver->energies();
  result.steps = solver->steps();
  result.time = solver->time();
  result.wall_seconds = wall;
  result.particle_steps_per_second = wall > 0 ? particle_steps / wall : 0.0;
  const std::vector<double> pv = probe_values(e);
  SummaryWriter summary;
  summary["status"] = result.ok ? "completed" : result.interrupted ? "interrupted" : "failed";
  if (!result.ok) {
    summary["error"] = result.error;
    if (!result.interrupted) summary["failed_step"] = result.failed_step;
    if (result.failed_particle >= 0) summary["failed_particle"] = result.failed_particle;
  }
  if (!sc.output.track.empty()) summary["tracked_particles"] = sc.output.track;
  summary["deck"] = restart ? restart->text("run.deck_file") : sc.file;
  if (restart) summary["restarted_from"] = opt.restart_from;
  JsonValue& probes = summary["probes"];
  probes = JsonValue::object();
  for (size_t k = 0; k < sc.probes.size(); ++k) {
    probes[sc.probes[k].name] = pv[k];
    result.probes.emplace_back(sc.probes[k].name, pv[k]);
  }
  if (nstages > 0) {
    summary["stages"] = stage_log;
    summary["main_stage_start"] = stage == nstages ? JsonValue(stage_start) : JsonValue();
  }
  if (penetration) {
    try {
      const FieldStore all = comm.distributed() ? gather_points(comm, solver->points()) : FieldStore{};
      if (root)
        penetration->finish(comm.distributed() ? all : solver->points(), opt.out_dir, sc.simulation.end_time,
                            summary["penetration"]);
    } catch (const std::exception& w) {
      spdlog::error("penetration analysis failed: {}", w.what());
    }
  }
  // What the discretisation itself reports (peridynamics: fragments and broken bonds).
  try {
    if (const auto values = solver->result_values(); !values.empty()) {
      JsonValue& sr = summary["solver_results"];
      sr = JsonValue::object();
      for (const auto& [k, v] : values) sr[k] = v;
    }
    if (const auto timing = solver->timing_values(); !timing.empty()) {
      JsonValue& tm = summary["timing"];
      tm = JsonValue::object();
      for (const auto& [k, v] : timing) tm[k + "_seconds"] = v;
    }
    const std::vector<ResultTable> tables = root ? solver->result_tables() : std::vector<ResultTable>{};
    for (const ResultTable& t : tables) {
      HistoryWriter csv((fs::path(opt.out_dir) / (t.name + ".csv")).string(), t.columns);
      for (const auto& row : t.rows) csv.row(row);
    }
    // No figure when interrupted: mpirun SIGKILLs the ranks odls_base_sigkill_timeout (1 s by
    // default) after it passed SIGTERM on, too soon for matplotlib; the restarted run draws it.
    report_fragments(tables, opt.out_dir, opt.plots && !result.interrupted, summary.root());  // a table named "fragments"
  } catch (const std::exception& w) {
    spdlog::error("the solver's results could not be written: {}", w.what());
  }
  JsonValue& st = summary["statistics"];
  st = JsonValue::object();
  st["solver"] = solver->name();
  st["steps"] = result.steps;
  st["end_time"] = result.time;
  st["wall_time"] = wall;
  st["threads"] = max_threads();
  st["ranks"] = comm.size();
  st["particles"] = comm.sum(static_cast<std::int64_t>(solver->points().size()));  // active at the end
  st["particles_seeded"] = seeded;
  std::int64_t deleted_points = 0;
  for (double n : e.removed_points_by_body) deleted_points += static_cast<std::int64_t>(n);
  st["particles_deleted"] = deleted_points;
  st["particle_steps"] = particle_steps;
  st["particle_steps_per_second"] = result.particle_steps_per_second;
  st["min_dt"] = std::isfinite(min_dt) ? min_dt : 0.0;
  st["worst_energy_drift"] = worst_drift;
  if (limiter.id >= 0) {
    JsonValue& lim = st["min_dt_set_by"];
    lim = JsonValue::object();
    lim["particle"] = limiter.id;
    lim["body"] = limiter.body >= 0 && limiter.body < static_cast<int>(sc.bodies.size()) ? sc.bodies[limiter.body].name : "";
    lim["time"] = limiter_time;
    lim["dt"] = limiter_dt;
    lim["wave_speed"] = limiter.wave_speed;
    lim["speed"] = limiter.speed;
    lim["J"] = limiter.J;
  }
  // (After the statistics: a new member of the summary may move the one `st` refers to.)
  if (deleted_points > 0) summary["deleted"] = deletions.summary(e);
  if (const auto warnings = deletions.probe_warnings(e); !warnings.empty()) {
    for (const auto& w : warnings) spdlog::warn("{}", w);
    summary["warnings"] = warnings;
  }
  JsonValue& en = summary["energy"];
  en = JsonValue::object();
  en["initial_total"] = total0;
  en["kinetic"] = e.kinetic;
  en["internal"] = e.internal;
  en["plastic_work"] = e.plastic;
  en["external_work"] = e.external;
  en["total"] = e.total();
  en["mass"] = e.mass;
  en["removed_mass"] = e.removed_mass;
  en["removed_energy"] = e.removed_energy;
  en["inserted_energy"] = e.inserted_energy;
  en["damping_work"] = e.damping;
  en["contact_work"] = e.contact;
  en["friction_work"] = e.friction;
  en["transfer_work"] = e.transfer;
  en["boundary_work"] = e.boundary;
  en["viscous_work"] = e.viscous;
  en["eroded_internal_energy"] = e.eroded;
  en["chemical_energy"] = e.chemical;
  en["scale"] = energy_scale;
  en["residual"] = e.total() - total0;
  en["residual_over_scale"] = energy_scale > 0 ? (e.total() - total0) / energy_scale : 0.0;
  // A number that is not a number is garbage, never a success (issue 11): the run is failed and
  // the summary says which values (they are written as null).
  const std::vector<std::string> bad = non_finite_numbers(summary.root());
  if (!bad.empty() && result.ok) {
    std::string list;
    for (size_t k = 0; k < bad.size() && k < 8; ++k) list += (k ? "; " : "") + bad[k];
    if (bad.size() > 8) list += fmt::format("; and {} more", bad.size() - 8);
    result.ok = false;
    result.error = "non-finite results at the end of the run: " + list +
                   " (a probe that selects no particle, or a value that overflowed; see the deck's probes)";
    spdlog::error("run failed: {}", result.error);
    summary["status"] = "failed";
    summary["error"] = result.error;
  }
  if (root) summary.write((fs::path(opt.out_dir) / "summary.json").string());
  if (physics_failure && checkpointing) {
    // The state at the start of the iteration that failed, as a checkpoint to restart from with
    // other settings. A failure leaves a half-updated state (inside a step) or one whose outputs
    // and stage bookkeeping were cut short (the drift guard, a stage that did not settle), so the
    // solver goes back to the newest checkpoint and replays the calls made before that iteration
    // (the run is deterministic; each step after its stable_dt, as the loop does).
    try {
      if (newest_checkpoint.empty()) throw Error("no checkpoint to replay from");
      solver->load_state(read_checkpoint_file(newest_checkpoint));
      const std::vector<SolverCall> calls(calls_since_checkpoint.begin(),
                                          calls_since_checkpoint.begin() + static_cast<std::ptrdiff_t>(good.calls));
      for (const SolverCall& c : calls) {
        if (c.stage >= 0) {
          solver->begin_stage(c.stage, c.damping);
        } else {
          (void)solver->stable_dt();
          solver->step(c.dt);
        }
      }
      write_checkpoint(good, "the start of the step that failed");
      result.checkpoint = newest_checkpoint;
    } catch (const std::exception& w) {
      spdlog::error("could not write a checkpoint of the last good step: {} (the newest checkpoint is {})", w.what(),
                    newest_checkpoint.empty() ? "none" : newest_checkpoint);
      result.checkpoint = newest_checkpoint;
    }
  }
  return result;
}

}  // namespace ballista
