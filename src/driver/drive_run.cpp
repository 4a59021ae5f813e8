#include "driver/drive_run.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <filesystem>

#include "driver/drive_history.hpp"
#include "io/atomic_file.hpp"
#include "io/summary_writer.hpp"

namespace ballista {

namespace {

JsonValue sym6(const Mat3& s) {
  JsonValue a = JsonValue::array();
  for (int k = 0; k < 6; ++k) a.push_back(s(kVoigtI[k], kVoigtJ[k]));
  return a;
}

}  // namespace

std::string drive_invariants_error(const DriveResult& r) {
  // Finite stresses whose invariants overflow (moduli near 1e308) are garbage too.
  for (const DriveRecord& rec : r.records)
    if (!std::isfinite(von_mises(rec.sigma)) || !std::isfinite(trace(rec.sigma)))
      return fmt::format("drive: the stress invariants are not finite at step {} (t = {:.6g} s; von Mises {}, "
                         "trace {}): the material's moduli or the strains are beyond double precision",
                         rec.step, rec.t, von_mises(rec.sigma), trace(rec.sigma));
  return {};
}

DriveResult drive_deck_point(const DriveDeck& deck, std::string& error) {
  const MaterialFactory* f = find_material(deck.material.model);
  if (!f) throw Error("unknown material model '" + deck.material.model + "'");
  const auto material = f->create(deck.material.name, deck.material.params);
  DriveResult r = drive_point(*material, deck.program, error);
  if (error.empty()) error = drive_invariants_error(r);
  return r;
}

DriveRunResult run_drive(const DriveDeck& deck, const std::string& out_dir) {
  namespace fs = std::filesystem;
  fs::create_directories(out_dir);
  write_file_atomic((fs::path(out_dir) / "resolved.yaml").string(), deck.resolved_yaml);

  DriveRunResult res;
  const auto wall0 = std::chrono::steady_clock::now();
  const DriveResult r = drive_deck_point(deck, res.error);
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  res.ok = res.error.empty();
  res.steps = r.steps;
  res.records = r.records.size();
  res.last = r.records.back();
  write_drive_history((fs::path(out_dir) / "history.csv").string(), r);

  SummaryWriter summary;
  summary["status"] = res.ok ? "completed" : "failed";
  if (!res.ok) summary["error"] = res.error;
  summary["deck"] = deck.file;
  JsonValue& m = summary["material"];
  m["name"] = deck.material.name;
  m["model"] = deck.material.model;
  JsonValue& p = summary["program"];
  const DriveProgram& prog = deck.program;
  if (!prog.table.empty()) {
    p["kind"] = "table";
    p["table_file"] = deck.table_file.empty() ? JsonValue() : JsonValue(deck.table_file);
    p["rows"] = static_cast<std::int64_t>(prog.table.size());
    p["substeps"] = prog.substeps;
    p["scale"] = deck.scale;
    p["noise"] = deck.noise;
    p["seed"] = static_cast<std::int64_t>(deck.seed);
  } else {
    p["kind"] = "legs";
    p["legs"] = static_cast<std::int64_t>(prog.legs.size());
    p["stress_tolerance"] = prog.stress_tolerance;
  }
  p["record_every"] = prog.record_every;
  JsonValue& st = summary["statistics"];
  st["steps"] = res.steps;
  st["records"] = static_cast<std::int64_t>(res.records);
  st["max_newton_iterations"] = r.max_iterations;
  st["wall_time"] = res.wall_seconds;
  JsonValue& fin = summary["final"];
  const DriveRecord& last = res.last;
  fin["t"] = last.t;
  fin["step"] = last.step;
  JsonValue F = JsonValue::array();
  for (double x : last.F.a) F.push_back(x);
  fin["F"] = F;
  fin["sigma"] = sym6(last.sigma);
  fin["sigma_bar"] = sym6(last.sigma_bar);
  fin["pressure"] = -trace(last.sigma) / 3.0;
  fin["von_mises"] = von_mises(last.sigma);
  JsonValue& state = fin["state"];
  state = JsonValue::object();
  for (size_t k = 0; k < r.state_names.size() && k < last.state.size(); ++k) state[r.state_names[k]] = last.state[k];
  fin["plastic_work_total"] = last.plastic_work_total;
  fin["internal_energy"] = last.internal_energy;
  // Backstop: any other number that is not a number fails the drive, never a success.
  if (const auto bad = non_finite_numbers(summary.root()); res.ok && !bad.empty()) {
    res.ok = false;
    res.error = "drive: non-finite results: " + bad.front() +
                (bad.size() > 1 ? fmt::format(" and {} more", bad.size() - 1) : "");
    summary["status"] = "failed";
    summary["error"] = res.error;
  }
  summary.write((fs::path(out_dir) / "summary.json").string());
  return res;
}

}  // namespace ballista
