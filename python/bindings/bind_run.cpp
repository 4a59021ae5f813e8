// run_deck: a run deck's text run in this process by run_simulation, the loop `ballista run`
// uses, so a run from Python writes the same results folder, bit for bit. The GIL is released
// while the run steps and taken again only to call the caller's progress callback.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <spdlog/spdlog.h>

#include "bindings.hpp"
#include "core/console_log.hpp"
#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "io/checkpoint_file.hpp"
#include "run/interrupt.hpp"
#include "run/penetration_plots.hpp"
#include "run/simulation.hpp"

namespace py = pybind11;

namespace ballista::python {

namespace {

py::dict report_dict(const ProgressReport& r) {
  py::dict d;
  d["phase"] = r.phase.empty() ? std::string("main") : r.phase;
  d["time"] = r.time;
  d["start"] = r.start;
  d["end"] = r.end;
  d["fraction"] = r.fraction;
  d["step"] = r.step;
  d["dt"] = r.dt;
  d["eta_seconds"] = r.eta_seconds;
  d["eta_is_bound"] = r.bounded;
  return d;
}

/// Hands the run's progress to the caller's callback: at a phase's first step, then at most every
/// `interval` wall seconds (a callback per step would cost more than a small step). The callback
/// stops the run (with a checkpoint, status "interrupted") by returning False or by raising; the
/// exception is raised again once the run has stopped and written its summary.
class ProgressRelay {
 public:
  ProgressRelay(py::object callback, double interval) : callback_(std::move(callback)), interval_(interval) {}

  void operator()(const ProgressReport& r) {
    const auto now = std::chrono::steady_clock::now();
    const bool new_phase = r.phase != phase_ || first_;
    if (!new_phase && std::chrono::duration<double>(now - last_).count() < interval_) return;
    first_ = false;
    phase_ = r.phase;
    last_ = now;
    py::gil_scoped_acquire gil;
    if (error_) return;
    try {
      const py::object answer = callback_(report_dict(r));
      if (!answer.is_none() && !answer.cast<bool>()) request_interrupt();
    } catch (py::error_already_set& e) {
      error_.emplace(std::move(e));
      request_interrupt();
    }
  }

  /// Raises what the callback raised, if it did.
  void rethrow() {
    if (error_) {
      py::error_already_set e = std::move(*error_);
      error_.reset();
      throw e;
    }
  }

 private:
  py::object callback_;
  double interval_;
  bool first_ = true;
  std::string phase_;
  std::chrono::steady_clock::time_point last_;
  std::optional<py::error_already_set> error_;
};

py::dict result_dict(const RunResult& r, const std::string& out_dir, bool by_caller) {
  py::dict d;
  d["status"] = r.ok ? "completed" : r.interrupted ? "interrupted" : "failed";
  d["interrupted_by"] = r.interrupted ? (by_caller ? "caller" : "signal") : "";
  d["error"] = r.error;
  d["failed_particle"] = r.failed_particle;
  d["failed_step"] = r.failed_step;
  d["steps"] = r.steps;
  d["time"] = r.time;
  d["wall_seconds"] = r.wall_seconds;
  d["particle_steps_per_second"] = r.particle_steps_per_second;
  py::dict probes;
  for (const auto& [name, value] : r.probes) probes[py::str(name)] = value;
  d["probes"] = probes;
  d["headlines"] = r.headlines;
  d["checkpoint"] = r.checkpoint;
  d["out_dir"] = out_dir;
  return d;
}

/// Marks the one run a process may hold at a time (the run loop's console, thread count and
/// signal handlers are the process's): a second run from another thread is refused.
class OneRunAtATime {
 public:
  OneRunAtATime() {
    if (running().exchange(true))
      throw Error("a run is already going in this process (from another thread): one at a time; "
                  "`ballista sweep` runs many side by side as processes");
  }
  ~OneRunAtATime() { running().store(false); }

 private:
  static std::atomic<bool>& running() {
    static std::atomic<bool> flag{false};
    return flag;
  }
};

/// Runs `sc` with `opt` (out_dir, threads, restart_from set by the caller); see run_deck.
py::dict execute(const Scenario& sc, RunOptions opt, bool plots, bool quiet, const py::object& progress,
                 double progress_interval) {
  opt.plots = plots;
  // The log's progress lines unless quiet or the caller follows the run itself.
  opt.progress = !quiet && progress.is_none();
  ProgressRelay relay(progress, progress_interval);
  if (!progress.is_none()) opt.on_progress = [&relay](const ProgressReport& r) { relay(r); };
  RunResult r;
  bool by_caller = false;
  {
    py::gil_scoped_release release;
    r = run_simulation(sc, opt);
    by_caller = interrupt_from_caller();
    clear_interrupt();
  }
  relay.rethrow();
  // The penetration figures `ballista run` draws (thesis seed 000 Figs. 7.4-7.7); a missing
  // matplotlib is a warning, as on the command line.
  if (plots && sc.penetration.enabled) {
    const std::string err = make_penetration_plots(opt.out_dir);
    if (!err.empty()) spdlog::warn("no penetration figures: {}", err);
  }
  return result_dict(r, opt.out_dir, by_caller);
}

py::dict run_deck(const std::string& text, const std::string& file_name, const std::vector<std::string>& overrides,
                  const std::string& out_dir, int threads, bool overwrite, bool plots, bool quiet,
                  const py::object& progress, double progress_interval) {
  const OneRunAtATime one;
  quiet ? quiet_console() : full_console();
  const Scenario sc = parse_deck(text, file_name, overrides);
  RunOptions opt;
  opt.out_dir = out_dir;
  opt.threads = threads;
  opt.overwrite = overwrite;
  return execute(sc, opt, plots, quiet, progress, progress_interval);
}

/// `ballista run --restart DIR`: the newest checkpoint's own deck, continued in its folder.
py::dict restart_run(const std::string& out_dir, const std::vector<std::string>& overrides, int threads, bool plots,
                     bool quiet, const py::object& progress, double progress_interval) {
  const OneRunAtATime one;
  quiet ? quiet_console() : full_console();
  const auto [path, deck_text] = newest_checkpoint(out_dir);
  const Scenario sc =
      parse_deck(deck_text, (std::filesystem::path(out_dir) / "resolved.yaml").string(), overrides);
  RunOptions opt;
  opt.out_dir = out_dir;
  opt.threads = threads;
  opt.restart_from = path;
  return execute(sc, opt, plots, quiet, progress, progress_interval);
}

}  // namespace

void bind_run(py::module_& m) {
  m.def("run_deck", &run_deck, py::arg("text"), py::arg("file_name"), py::arg("overrides"), py::arg("out_dir"),
        py::arg("threads"), py::arg("overwrite"), py::arg("plots"), py::arg("quiet"), py::arg("progress"),
        py::arg("progress_interval"),
        "Runs a deck given as YAML text (file_name names it in errors and anchors its relative paths); "
        "returns the run's result as a dict.");
  m.def("restart_run", &restart_run, py::arg("out_dir"), py::arg("overrides"), py::arg("threads"), py::arg("plots"),
        py::arg("quiet"), py::arg("progress"), py::arg("progress_interval"),
        "Continues the run in out_dir from its newest checkpoint (the checkpoint's deck; overrides may change "
        "only what a restart may change).");
}

}  // namespace ballista::python
