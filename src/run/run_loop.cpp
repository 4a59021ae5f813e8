#include "run/run_loop.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "analysis/penetration_probe.hpp"
#include "core/energy_terms.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/warning_log.hpp"
#include "geometry/seeding.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint_file.hpp"
#include "points/point_exchange.hpp"
#include "points/solver_registry.hpp"
#include "run/interrupt.hpp"
#include "run/restart_checks.hpp"
#include "run/run_banner.hpp"

namespace ballista {

namespace fs = std::filesystem;

namespace {

/// "particle 12 of body 'bar' (wave speed 4000 m/s, speed 200 m/s, J 0.98[, cell 0.00025 m])".
std::string describe_limiter(const Scenario& sc, const StepLimiter& l) {
  if (l.id < 0) return "no particle";
  const std::string body =
      l.body >= 0 && l.body < static_cast<int>(sc.bodies.size()) ? " of body '" + sc.bodies[l.body].name + "'" : "";
  const std::string cell = l.cell > 0.0 ? fmt::format(", cell {:.4g} m", l.cell) : "";
  return fmt::format("particle {}{} ({} {:.4g} m/s, speed {:.4g} m/s, J {:.4g}{})", l.id, body,
                     l.viscous ? "bulk-viscosity signal" : "wave speed", l.wave_speed, l.speed, l.J, cell);
}

/// Refuses a run whose estimated step count (simulated time / first stable step) exceeds
/// simulation.step_limit: a cfl of 1e-12 or a max_dt of 1e-300 would otherwise promise an ETA of
/// ~1e11 s instead of an error.
void check_step_estimate(const Scenario& sc, const Solver& solver, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) return;  // the loop's own check reports it with its step
  const double steps = estimate_steps(sc, dt).most;  // the main stage plus the longest stages
  const double span = steps * dt;
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

}  // namespace

RunLoop::RunLoop(const Scenario& sc, const RunOptions& opt)
    : sc_(sc),
      opt_(opt),
      comm_(Communicator::world()),
      root_(comm_.rank() == 0),
      nstages_(static_cast<int>(sc.stages.size())) {
  // The warnings from here on are this run's (summary.json "warnings").
  record_warnings();
  warning_mark_ = warning_count();
  // Refused before anything is written.
  if (const SolverFactory* f = find_solver(sc.simulation.solver)) check_distributed(sc, *f, comm_);
  // Rank 0 holds the results folder for the run (io/run_folder.hpp): another run into it is
  // refused, and a new run removes exactly the files of the previous one. A restart continues
  // the folder it was written in: nothing there is cleared.
  if (root_ && !opt.folder_held)
    folder_.emplace(opt.out_dir, opt.restart_from.empty() ? RunFolder::Mode::NewRun : RunFolder::Mode::Continue,
                    opt.overwrite);
  if (!opt.restart_from.empty()) {
    restart_ = read_checkpoint_file(opt.restart_from);  // every rank reads it
    check_restart_changes(*restart_, sc, opt.restart_from);
    check_layout(*restart_, sc, opt.restart_from);
    // Checkpoints newer than the one restarted from belong to the abandoned continuation.
    if (root_)
      if (const int n = remove_checkpoints_after(opt.out_dir, opt.restart_from))
        spdlog::info("removed {} checkpoints newer than {}", n, opt.restart_from);
  } else if (root_) {
    if (folder_ && folder_->removed() > 0)
      spdlog::info("removed {} output files of an earlier run from {}", folder_->removed(), opt.out_dir);
    write_file_atomic((fs::path(opt.out_dir) / "resolved.yaml").string(), sc.resolved_yaml);
  }
  clear_interrupt();
  request_threads(opt.threads > 0 ? opt.threads : sc.simulation.threads,  // clamped to the cores present
                  opt.threads > 0 ? "--threads" : "simulation.threads");

  solver_ = make_solver(sc, comm_);
  // Constants the solver derived from the deck (peridynamic bond constants), echoed as comments.
  // A restart writes the deck it continues with (its end time, outputs and guards may differ).
  if (const std::string derived = solver_->derived_constants(); root_ && (restart_ || !derived.empty()))
    write_file_atomic((fs::path(opt.out_dir) / "resolved.yaml").string(), sc.resolved_yaml + derived);
  FieldStore& pts = solver_->points();
  probes_ = make_probes(sc);
  tension_ = TensionWatch(sc);
  for (const auto& probe : probes_) probe->check(pts);
  writer_.emplace(opt.out_dir, output_fields(sc, pts), sc.output.domains,
                  sc.simulation.dimension == Dimension::ThreeD ? 3 : 2);
  // A particle file of the current state; several ranks write it together (parallel HDF5, each
  // rank its particles in rank order; io/particle_writer.hpp): collective.
  writer_->set_communicator(comm_);
  std::vector<std::string> body_names, material_names;
  for (const auto& b : sc.bodies) body_names.push_back(b.name);
  for (const auto& m : sc.materials) material_names.push_back(m.name);
  writer_->set_names(std::move(body_names), std::move(material_names));
  if (sc.simulation.dimension != Dimension::ThreeD)
    writer_->set_extensive(extensive_point_fields(),
                           sc.simulation.dimension == Dimension::Axisymmetric ? "/rad" : "/m");
  open_history();
  seeded_ = comm_.sum(static_cast<std::int64_t>(pts.size() + solver_->pending_points()));
  tracker_.emplace(sc, opt.out_dir, seeded_);
  tracked_ids_ = std::set<std::int64_t>(sc.output.track.begin(), sc.output.track.end());
  // The first stable step (none on a restart, which keeps the solver's state as checkpointed).
  const double dt0 = restart_ ? 0.0 : solver_->stable_dt();
  if (!restart_) check_step_estimate(sc, *solver_, dt0);
  const std::string banner = run_banner(sc, *solver_, dt0, comm_.sum(solver_->pending_points()), comm_);
  if (root_) spdlog::info("{}", banner);
  start_clocks();
  deletions_.emplace(sc, solver_->energies());
  // A restart's own checkpoint is where a failure before its first checkpoint replays from.
  if (restart_) newest_checkpoint_ = opt.restart_from;
  wall_start_ = wall_of_last_checkpoint_ = std::chrono::steady_clock::now();
}

RunLoop::~RunLoop() = default;

/// history.csv's columns: time and step, the energy audit, the deck's probes, the stage, the
/// solver's own columns and the penetration analysis.
void RunLoop::open_history() {
  columns_ = {"time", "step", "dt"};
  for (const EnergyTerm& t : kEnergyTerms) columns_.push_back(t.column);
  for (const auto& pr : sc_.probes) columns_.push_back(pr.name);
  if (nstages_ > 0) columns_.push_back("stage");
  const std::vector<std::string> solver_columns = solver_->history_columns();
  columns_.insert(columns_.end(), solver_columns.begin(), solver_columns.end());
  if (sc_.penetration.enabled) {
    penetration_ = std::make_unique<PenetrationProbe>(sc_);
    for (const auto& c : penetration_->columns()) columns_.push_back(c);
  }
  // Columns where nan is a documented "not applicable yet" (docs/penetration.md), not garbage.
  nan_allowed_.assign(columns_.size(), false);
  for (const std::string& c : PenetrationProbe::nan_when_not_applicable())
    for (size_t k = 0; k < columns_.size(); ++k)
      if (penetration_ && columns_[k] == c) nan_allowed_[k] = true;
  const std::string path = (fs::path(opt_.out_dir) / "history.csv").string();
  if (root_)
    history_ = restart_ ? std::make_unique<HistoryWriter>(path, columns_, restart_->integer("run.history_bytes"))
                        : std::make_unique<HistoryWriter>(path, columns_);
}

/// The loop's clocks and energy reference: a new run's, or the checkpoint's with the deck's
/// (possibly changed) end time.
void RunLoop::start_clocks() {
  interval_ = sc_.output.interval > 0 ? sc_.output.interval : sc_.simulation.end_time;
  checkpointing_ = sc_.output.checkpoint_interval > 0 || opt_.checkpoint_minutes > 0;
  if (!restart_) {
    const EnergyTotals e0 = solver_->energies();
    rs_.total0 = e0.total();
    // The end time and output times are known once the main stage starts (stage_start + end_time).
    rs_.end = nstages_ > 0 ? RunState::kInf : sc_.simulation.end_time;
    rs_.next_output = nstages_ > 0 ? rs_.end : interval_;
    rs_.next_checkpoint = sc_.output.checkpoint_interval > 0 ? sc_.output.checkpoint_interval : RunState::kInf;
    rs_.energy_scale = energy_scale_of(e0);
    return;
  }
  solver_->load_state(*restart_);
  rs_.load(*restart_);
  if (!root_) rs_.particle_steps = 0.0;  // the checkpoint holds the total (counted once, on rank 0)
  ParticleWriter::State ws;
  ws.count = static_cast<int>(restart_->integer("run.outputs"));
  ws.xdmf_body = restart_->text("run.xdmf");
  writer_->restore(ws);  // removes the particle files written after the checkpoint (rank 0)
  if (penetration_) penetration_->load_state(*restart_);
  tension_.load(*restart_);
  if (!tracker_->empty()) {  // rank 0's: it alone writes the tracks
    if (!restart_->has("tracks.open"))
      throw Error("the checkpoint was written without output.track.ids; tracks cannot start in the middle of a "
                  "run (their F-tables would miss the steps before): run the deck from the start to track");
    if (root_) tracker_->load_state(*restart_);
  }
  // The deck may have changed the end (--set simulation.end_time=...): the main stage ends
  // end_time after it began; the output clock stays where it was, within the new end.
  if (rs_.stage == nstages_) {
    rs_.end = (nstages_ > 0 ? rs_.stage_start : 0.0) + sc_.simulation.end_time;
    if (rs_.end < solver_->time() * (1.0 - 1e-12))
      throw DeckError(sc_.file, 0, 0, "simulation.end_time",
                      fmt::format("simulation.end_time = {:g} s ends the run at t = {:.6g} s, before the "
                                  "checkpoint's t = {:.6g} s: nothing is left to run; give a later end time",
                                  sc_.simulation.end_time, rs_.end, solver_->time()));
    rs_.next_output = std::min(rs_.next_output, rs_.end);
    if (rs_.next_output <= solver_->time()) rs_.next_output = std::min(rs_.end, solver_->time() + interval_);
  }
  if (sc_.output.checkpoint_interval <= 0)
    rs_.next_checkpoint = RunState::kInf;
  else if (!std::isfinite(rs_.next_checkpoint))
    rs_.next_checkpoint = solver_->time() + sc_.output.checkpoint_interval;
  spdlog::info("restarted from {} at step {}, t = {:.6g} s", opt_.restart_from, solver_->steps(), solver_->time());
}

RunResult RunLoop::run() {
  if (!restart_) start_run();
  start_progress();
  try {
    const InterruptScope signals;  // SIGTERM / SIGINT checkpoint and stop, during the steps only
    step_loop();
    if (interrupted_) {
      // No final particle file: the checkpoint is where the run continues (ballista run --restart).
      result_.ok = false;
      result_.interrupted = true;
      result_.checkpoint = newest_checkpoint_;
      result_.error = fmt::format("interrupted by {} at step {} (t = {:.6g} s); continue with ballista run "
                                  "--restart {}",
                                  interrupt_from_caller() ? "the caller" : "a signal", solver_->steps(),
                                  solver_->time(), opt_.out_dir);
      spdlog::warn("{}", result_.error);
    } else {
      write_output();
    }
  } catch (const PhysicsError& err) {
    on_physics_failure(err);
  }
  if (progress_) progress_->finish();
  const std::chrono::duration<double> this_segment = std::chrono::steady_clock::now() - wall_start_;
  write_summary(rs_.wall_before + this_segment.count());
  if (physics_failure_ && checkpointing_) checkpoint_last_good_step();
  return result_;
}

/// A new run's first outputs: the initial particles, the first stage, the first history row and
/// the initial checkpoint (where a failing run replays from).
void RunLoop::start_run() {
  write_output();
  if (nstages_ > 0) {
    begin_stage(0, sc_.stages[0].damping);
    spdlog::info("stage '{}' begins (damping {} 1/s)", sc_.stages[0].name, sc_.stages[0].damping);
  }
  history_row(0.0);
  record_tracks(false);
  if (checkpointing_) write_checkpoint(marks_now(), "initial state");
}

void RunLoop::step_loop() {
  // Stop within a relative round-off of the end time instead of taking a sliver step.
  while (solver_->time() < rs_.end * (1.0 - 1e-12)) {
    if (sc_.simulation.max_steps > 0 && solver_->steps() >= sc_.simulation.max_steps) {
      spdlog::warn("simulation.max_steps = {} reached at t = {:.6g} s of {:.6g} s: the run ends early",
                   sc_.simulation.max_steps, solver_->time(), rs_.end);
      break;
    }
    if (checkpointing_) good_ = marks_now();
    const double dt = next_dt();
    rs_.particle_steps += static_cast<double>(solver_->points().size());
    solver_->step(dt);
    rs_.dt = dt;
    if (checkpointing_) calls_since_checkpoint_.push_back({dt, -1, 0.0});
    record_tracks(false);
    if (rs_.stage < nstages_) {
      after_preparation_step(dt);
      if (rs_.stage < nstages_) progress_->update(solver_->time(), solver_->steps(), dt);
      if (after_step()) break;
      continue;
    }
    const bool at_output = solver_->time() >= rs_.next_output * (1.0 - 1e-12);
    bool at_end = solver_->time() >= rs_.end * (1.0 - 1e-12);
    if (solver_->steps() % std::max(1, sc_.output.history_every) == 0 || at_output || at_end) {
      record_history(dt);
      // penetration.end_when_spent: the main stage ends here (rank 0 keeps the series).
      if (!at_end && penetration_ && sc_.penetration.end_when_spent > 0.0 &&
          comm_.any(root_ && penetration_->spent())) {
        spdlog::info("the penetrator is spent at t = {:.6g} s (its kinetic energy is at most {:g} of its peak): the "
                     "main stage ends",
                     solver_->time(), sc_.penetration.end_when_spent);
        rs_.end = solver_->time();
        at_end = true;
      }
    }
    if (at_output && !at_end) {
      write_output();
      rs_.next_output += interval_;
      if (rs_.next_output > rs_.end) rs_.next_output = rs_.end;
    }
    progress_->update(solver_->time(), solver_->steps(), dt);
    if (after_step()) break;
  }
}

/// The progress of the phase now running: a stage (to its fixed end, or at most to its
/// max_duration when a criterion ends it) or the main stage.
void RunLoop::start_progress() {
  if (progress_) progress_->finish();
  const bool enabled = opt_.progress && root_;
  if (rs_.stage == nstages_) {
    progress_ = std::make_unique<Progress>("", rs_.stage_start, rs_.end, false, enabled);
  } else {
    const StageSpec& st = sc_.stages[rs_.stage];
    const double span = st.until.empty() ? st.duration : st.max_duration;
    progress_ = std::make_unique<Progress>("stage '" + st.name + "'", rs_.stage_start, rs_.stage_start + span,
                                           !st.until.empty(), enabled);
  }
  if (root_ && opt_.on_progress) progress_->observe(opt_.on_progress);
}

/// The next step: the stable step (refused when it collapsed or the step count ran out), landing
/// exactly on output times, the end time and the end of a fixed-length stage.
double RunLoop::next_dt() {
  double dt = solver_->stable_dt();
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw PhysicsError(fmt::format("time step collapsed (dt = {:.6g} s) at step {}, set by {}", dt, solver_->steps(),
                                   describe_limiter(sc_, solver_->step_limiter())));
  if (solver_->steps() >= sc_.simulation.step_limit)
    throw PhysicsError(fmt::format(
        "the run reached simulation.step_limit = {} steps at t = {:.6g} s of {:.6g} s (dt = {:.6g} s, set by {}): "
        "the time step has collapsed; raise simulation.step_limit to insist",
        sc_.simulation.step_limit, solver_->time(), rs_.end, dt, describe_limiter(sc_, solver_->step_limiter())));
  // The smallest stable step is what a collapsing time step shows (thesis ch. 6), not the
  // slivers taken to land on output and end times.
  const bool new_low = dt < 0.9 * rs_.limiter_dt;
  // What holds the step over the run, not only at its low (run/step_tally.hpp); a step that
  // simulation.max_dt set is no point's.
  const bool sample = solver_->steps() % kStepTallyInterval == 0;
  const bool by_max_dt = sc_.simulation.max_dt > 0.0 && dt >= sc_.simulation.max_dt;
  StepLimiter limiter;
  if (new_low || (sample && !by_max_dt)) limiter = solver_->step_limiter();
  if (new_low) {
    // A new low of the stable step (by 10 %): remember which point sets it.
    rs_.limiter = limiter;
    rs_.limiter_dt = dt;
    rs_.limiter_time = solver_->time();
  }
  rs_.min_dt = std::min(rs_.min_dt, dt);
  if (sample) {
    if (by_max_dt)
      ++rs_.step_tally.max_dt_samples;
    else
      rs_.step_tally.add(limiter);
  }
  dt = std::min({solver_->land_step(dt), rs_.end - solver_->time(), rs_.next_output - solver_->time()});
  if (rs_.stage < nstages_) {
    const StageSpec& st = sc_.stages[rs_.stage];
    const double stage_end = rs_.stage_start + (st.until.empty() ? st.duration : st.max_duration);
    dt = std::min(dt, stage_end - solver_->time());
  }
  return dt;
}

/// After a step of a preparation stage: its end by duration or by stress equilibrium, and the
/// history row of a step that did not end it (next_stage writes that one).
void RunLoop::after_preparation_step(double dt) {
  const int stage_before = rs_.stage;
  const StageSpec& st = sc_.stages[rs_.stage];
  const double elapsed = solver_->time() - rs_.stage_start;
  if (st.until.empty()) {
    if (elapsed >= st.duration * (1.0 - 1e-12)) next_stage("duration", nullptr);
  } else {
    check_equilibrium_stage(st, elapsed);
  }
  if (rs_.stage == stage_before && solver_->steps() % std::max(1, sc_.output.history_every) == 0)
    record_history(dt);
}

/// A stage that ends at stress equilibrium: checked every check_every steps after min_duration;
/// one that has not settled by max_duration stops the run.
void RunLoop::check_equilibrium_stage(const StageSpec& st, double elapsed) {
  const bool last_chance = elapsed >= st.max_duration * (1.0 - 1e-12);
  if (!((elapsed >= st.min_duration && solver_->steps() % st.check_every == 0) || last_chance)) return;
  EquilibriumCheck c;
  if (!comm_.distributed()) {
    c = check_stress_equilibrium(st, body_index(sc_, st.body), solver_->points());
  } else {
    // Over every rank's particles on rank 0; its verdict goes to all (they end the stage
    // together).
    const FieldStore all = gather_points(comm_, solver_->points());
    if (root_) c = check_stress_equilibrium(st, body_index(sc_, st.body), all);
    comm_.broadcast(&c, sizeof c, 0);
  }
  if (c.satisfied && elapsed >= st.min_duration) {
    next_stage(st.until, &c);
  } else if (last_chance) {
    throw PhysicsError("stage '" + st.name + "' did not reach stress equilibrium within its max_duration of " +
                       fmt::format("{:.6g}", st.max_duration) + " s (step " + std::to_string(solver_->steps()) +
                       "): " + describe_equilibrium(st, c) +
                       "; raise max_duration, or tune the damping (thesis seed 000 §5.1: near-critical damping)");
  }
}

void RunLoop::begin_stage(int stage, double damping) {
  solver_->begin_stage(stage, damping);
  calls_since_checkpoint_.push_back({0.0, stage, damping});
}

/// Ends the current preparation stage: log it, snapshot the particles, start the next stage.
void RunLoop::next_stage(const std::string& how, const EquilibriumCheck* check) {
  const StageSpec& st = sc_.stages[rs_.stage];
  StageRecord rec;
  rec.name = st.name;
  rec.start_time = rs_.stage_start;
  rec.end_time = solver_->time();
  rec.ended_by = how;
  rec.damping = st.damping;
  if (check) {
    rec.checked = true;
    rec.worst_deviation = check->worst;
    rec.worst_particle = check->worst_id;
    rec.fraction_within = check->within;
  }
  rs_.stages.push_back(rec);
  spdlog::info("stage '{}' ended at t = {:.4g} s ({}){}", st.name, solver_->time(), how,
               check ? ": " + describe_equilibrium(st, *check) : std::string());
  record_history(rs_.dt);
  write_output();
  ++rs_.stage;
  rs_.stage_start = solver_->time();
  const double damping = rs_.stage < nstages_ ? sc_.stages[rs_.stage].damping : sc_.simulation.damping;
  begin_stage(rs_.stage, damping);
  if (rs_.stage < nstages_) {
    spdlog::info("stage '{}' begins (damping {} 1/s)", sc_.stages[rs_.stage].name, damping);
  } else {
    rs_.end = rs_.stage_start + sc_.simulation.end_time;
    rs_.next_output = std::min(rs_.end, rs_.stage_start + interval_);
    spdlog::info("main stage begins at t = {:.4g} s (damping {} 1/s), runs to {:.4g} s", rs_.stage_start, damping,
                 rs_.end);
  }
  start_progress();
}

void RunLoop::write_output() {
  writer_->write(solver_->time(), solver_->steps(), solver_->points(), solver_->output_nodes());
}

/// A physics failure: the result says what and where, the tracked particles record the failing
/// step, and the failing state goes to a new output file (earlier outputs stay untouched).
void RunLoop::on_physics_failure(const PhysicsError& err) {
  if (progress_) progress_->finish();
  result_.ok = false;
  result_.error = err.what();
  result_.failed_step = solver_->steps();
  // The only dynamic_cast of the run loop: on the error's type, never on the solver.
  if (const auto* pe = dynamic_cast<const ParticleError*>(&err)) result_.failed_particle = pe->id();
  try {
    record_tracks(true);
  } catch (const std::exception& w) {
    spdlog::error("could not record the failing step of the tracked particles: {}", w.what());
  }
  spdlog::error("run stopped: {}", err.what());
  physics_failure_ = true;
  try {
    write_output();
  } catch (const std::exception& w) {
    spdlog::error("could not write the failing state: {}", w.what());
  }
}

}  // namespace ballista
