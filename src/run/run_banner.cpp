#include "run/run_banner.hpp"

#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "core/system_memory.hpp"

namespace ballista {

namespace {

/// "12,345": particle counts are read at a glance.
std::string grouped(std::int64_t n) {
  std::string s = std::to_string(n < 0 ? -n : n), out;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (k > 0 && (s.size() - k) % 3 == 0) out += ',';
    out += s[k];
  }
  return n < 0 ? "-" + out : out;
}

std::string dimension_word(Dimension d) {
  switch (d) {
    case Dimension::ThreeD: return "3D";
    case Dimension::Axisymmetric: return "axisymmetric";
    case Dimension::PlaneStrain: return "2D plane strain";
  }
  return "";
}

}  // namespace

StepEstimate estimate_steps(const Scenario& sc, double dt) {
  StepEstimate e;
  if (!(dt > 0.0) || !std::isfinite(dt)) return e;
  double least = sc.simulation.end_time, most = sc.simulation.end_time;
  for (const StageSpec& st : sc.stages) {
    least += st.until.empty() ? st.duration : st.min_duration;
    most += st.until.empty() ? st.duration : st.max_duration;
  }
  e.least = least / dt;
  e.most = most / dt;
  return e;
}

std::string run_banner(const Scenario& sc, Solver& solver, double dt, std::int64_t pending, const Communicator& comm) {
  const FieldStore& pts = solver.points();
  std::vector<std::int64_t> per_body(sc.bodies.size(), 0);
  if (pts.has(kBodyIndex.name())) {
    const std::int64_t* body = pts.ints(kBodyIndex);
    for (Index p = 0; p < pts.size(); ++p)
      if (body[p] >= 0 && body[p] < static_cast<std::int64_t>(per_body.size())) ++per_body[body[p]];
  }
  std::int64_t total = 0;
  std::string bodies, later;  // a body with no point yet is one inserted during the run (a jet)
  for (std::size_t b = 0; b < per_body.size(); ++b) {
    const std::int64_t n = comm.sum(per_body[b]);
    total += n;
    if (n == 0 && pending > 0)
      later += (later.empty() ? "" : ", ") + sc.bodies[b].name;
    else
      bodies += fmt::format("{}{} {} ({})", bodies.empty() ? "" : ", ", sc.bodies[b].name, grouped(n),
                            sc.bodies[b].material);
  }
  const double resident = comm.sum(resident_bytes());
  std::string text = fmt::format("{} solver, {}, {} thread{} x {} rank{}; {} particles: {}", solver.name(),
                                 dimension_word(sc.simulation.dimension), max_threads(), max_threads() == 1 ? "" : "s",
                                 comm.size(), comm.size() == 1 ? "" : "s", grouped(total), bodies);
  if (pending > 0)
    text += fmt::format("; {} more inserted during the run{}", grouped(pending), later.empty() ? "" : " (" + later + ")");
  text += fmt::format("\n  memory after set-up: {}", format_bytes(resident));
  if (dt > 0.0 && std::isfinite(dt)) {
    const StepEstimate e = estimate_steps(sc, dt);
    const std::string steps = std::llround(e.least) == std::llround(e.most)
                                  ? fmt::format("about {}", grouped(std::llround(e.most)))
                                  : fmt::format("about {} to {} (as the stages end)", grouped(std::llround(e.least)),
                                                grouped(std::llround(e.most)));
    text += fmt::format(
        "\n  steps: {} at the starting stable step {:.3g} s (the step shrinks when impacts compress or speed up "
        "the material)",
        steps, dt);
  }
  return text;
}

}  // namespace ballista
