#include "run/sweep.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <thread>

#include "deck/deck_overrides.hpp"
#include "deck/deck_reader.hpp"

extern char** environ;

namespace ballista {

namespace fs = std::filesystem;

namespace {

std::string describe(const std::vector<SweepAxis>& axes, const std::vector<std::string>& values) {
  std::string s;
  for (size_t a = 0; a < axes.size(); ++a) s += (a ? ", " : "") + axes[a].key + "=" + values[a];
  return s;
}

bool sets_threads(const std::vector<std::string>& overrides, const std::string& deck) {
  for (const auto& t : overrides)
    if (parse_override(t, deck).key_path == "simulation.threads") return true;
  return false;
}

/// The last non-empty lines of a run's log (its error message when it stopped before a summary).
std::string log_tail(const fs::path& log, size_t max_lines = 3) {
  std::ifstream in(log);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);)
    if (l.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(l);
  std::string s;
  for (size_t k = lines.size() > max_lines ? lines.size() - max_lines : 0; k < lines.size(); ++k)
    s += (s.empty() ? "" : " | ") + lines[k];
  return s;
}

/// Starts `exe run deck -o dir -q --overwrite --set ...` with stdout and stderr going to dir/log.txt.
pid_t launch(const std::string& exe, const std::string& deck, const SweepRunSpec& r) {
  fs::create_directories(r.dir);
  fs::remove(r.dir / "summary.json");  // a summary left by an earlier sweep must not be read as this run's
  // --overwrite: the folder already holds the sweep's own log.txt (io/run_folder.hpp).
  std::vector<std::string> args{exe, "run", deck, "-o", r.dir.string(), "-q", "--overwrite"};
  for (const auto& o : r.overrides) {
    args.push_back("--set");
    args.push_back(o);
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log = (r.dir / "log.txt").string();
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw Error("sweep: cannot start '" + exe + "': " + std::strerror(rc));
  return pid;
}

/// The table row of a finished run from its exit status, summary.json and log.
SweepRow collect(const SweepRunSpec& r, int wait_status) {
  SweepRow row;
  row.index = r.index;
  row.values = r.values;
  const bool exited = WIFEXITED(wait_status);
  const int code = exited ? WEXITSTATUS(wait_status) : -1;
  row.status = exited && code == 0 ? "completed" : "failed";
  YAML::Node summary;
  const fs::path sp = r.dir / "summary.json";
  if (fs::exists(sp)) {
    try {
      summary = YAML::LoadFile(sp.string());  // JSON is YAML 1.2 flow syntax
      row.scalars = flatten_summary(summary, {"status", "error"});
    } catch (const std::exception& e) {
      if (row.status == "completed") row.status = "failed";
      row.error = "unreadable summary.json: " + std::string(e.what());
    }
  }
  if (row.status != "completed" && row.error.empty()) {
    if (summary.IsMap() && summary["error"] && summary["error"].IsScalar())
      row.error = summary["error"].Scalar();
    else if (!exited)
      row.error = "killed by signal " + std::to_string(WTERMSIG(wait_status));
    else
      row.error = "exit status " + std::to_string(code) + ": " + log_tail(r.dir / "log.txt");
  }
  return row;
}

}  // namespace

int sweep_threads_per_run(int cores, int jobs) {
  return std::max(1, cores / std::max(1, jobs));
}

SweepPlan plan_sweep(const SweepOptions& o) {
  if (o.jobs < 1) throw Error("--jobs " + std::to_string(o.jobs) + ": expected a positive number of runs at a time");
  SweepPlan plan;
  plan.axes = parse_vary_options(o.vary);
  if (plan.axes.empty()) throw Error("sweep: give at least one --vary key.path=value1,value2,...");
  std::vector<std::string> varied_keys;
  for (const auto& a : plan.axes) varied_keys.push_back(a.key + "=x");
  if (o.jobs > 1 && !sets_threads(o.set, o.deck) && !sets_threads(varied_keys, o.deck)) {
    const int cores = o.cores > 0 ? o.cores : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    plan.threads_per_run = sweep_threads_per_run(cores, o.jobs);
  }
  const auto combos = sweep_product(plan.axes);
  for (size_t k = 0; k < combos.size(); ++k) {
    SweepRunSpec r;
    r.index = static_cast<int>(k);
    r.values = combos[k];
    // Order: threads first, so an explicit --set simulation.threads would win; then --set, then the
    // varied values.
    if (plan.threads_per_run > 0) r.overrides.push_back("simulation.threads=" + std::to_string(plan.threads_per_run));
    r.overrides.insert(r.overrides.end(), o.set.begin(), o.set.end());
    for (size_t a = 0; a < plan.axes.size(); ++a) r.overrides.push_back(plan.axes[a].key + "=" + r.values[a]);
    r.dir = o.out_dir / ("run_" + std::to_string(k));
    try {  // validate only: a bad key or value stops the sweep before any run
      (void)read_deck(o.deck, r.overrides);
    } catch (const DeckError& e) {
      throw SweepDeckError("run " + std::to_string(k) + " (" + describe(plan.axes, r.values) + "): " + e.what());
    }
    plan.runs.push_back(std::move(r));
  }
  return plan;
}

SweepTable run_sweep(const SweepOptions& o) {
  const SweepPlan plan = plan_sweep(o);
  if (o.executable.empty()) throw Error("sweep: no executable to run the decks with");
  const size_t n = plan.runs.size();
  if (!o.quiet)
    std::cout << fmt::format("sweep: {} runs, {} at a time{} -> {}\n", n, std::min<size_t>(n, o.jobs),
                             plan.threads_per_run > 0
                                 ? fmt::format(", simulation.threads = {} each", plan.threads_per_run)
                                 : "",
                             o.out_dir.string())
              << std::flush;
  std::vector<SweepRow> rows(n);
  std::map<pid_t, size_t> running;
  std::map<pid_t, std::chrono::steady_clock::time_point> started;
  size_t next = 0, done = 0;
  while (done < n) {
    while (next < n && running.size() < static_cast<size_t>(o.jobs)) {
      pid_t pid = -1;
      try {
        pid = launch(o.executable, o.deck, plan.runs[next]);
      } catch (const std::exception& e) {  // this run cannot start: record it, go on with the others
        rows[next] = SweepRow{plan.runs[next].index, plan.runs[next].values, "failed", e.what(), {}};
        ++next;
        ++done;
        continue;
      }
      running[pid] = next++;
      started[pid] = std::chrono::steady_clock::now();
    }
    if (running.empty()) continue;  // every remaining run failed to start
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw Error(std::string("sweep: waitpid: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not one of ours
    const SweepRunSpec& r = plan.runs[it->second];
    rows[it->second] = collect(r, status);
    ++done;
    if (!o.quiet) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started[pid]).count();
      const SweepRow& row = rows[it->second];
      std::cout << fmt::format("[{}/{}] run_{} {}: {} in {:.1f} s{}\n", done, n, r.index, describe(plan.axes, r.values),
                               row.status, s,
                               row.error.empty() ? "" : " (" + row.error.substr(0, row.error.find('\n')) + ")")
                << std::flush;
    }
    running.erase(it);
  }
  SweepTable table(plan.axes);
  for (auto& row : rows) table.add(std::move(row));
  table.write(o.out_dir);
  for (const auto& step : o.post_steps) step(table, o.out_dir);
  return table;
}

}  // namespace ballista
