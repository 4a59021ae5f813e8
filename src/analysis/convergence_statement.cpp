#include "analysis/convergence_statement.hpp"

#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace ballista {

namespace {

/// The number at a dotted key ("holes.casing.mean_diameter") of an object; null if absent.
JsonValue at_dotted(const JsonValue& obj, const std::string& key) {
  const JsonValue* v = &obj;
  std::istringstream parts(key);
  std::string part;
  while (std::getline(parts, part, '.')) {
    if (v->kind() != JsonValue::Kind::Object || !v->contains(part)) return JsonValue();
    v = &v->at(part);
  }
  if (v->kind() != JsonValue::Kind::Number && v->kind() != JsonValue::Kind::Int) return JsonValue();
  return JsonValue(v->as_number());
}

/// Relative difference within which a run reproduces a checked configuration's recorded value. The
/// runs are deterministic for any thread count, but not across processors: the Release build is
/// compiled for the machine it is built on, and a build of one commit for another instruction set
/// reads the deck as written's tunnel depth 0.47 % and its casing hole 0.12 % away from the record
/// (AVX-512 against AVX2, docs/validation.md, "The perforation demo under refinement"). Four times
/// that is round-off carried through the run; beyond it another end time or code path made the
/// number, and the record no longer describes the run.
constexpr double kReproduced = 0.02;

/// Whether a study's level cell h is the cell `cell` (to 1e-6 of h: the record's cells are the
/// study's --levels, written in decimal).
bool same_level(double h, double cell) { return std::abs(h - cell) <= 1e-6 * h; }

}  // namespace

bool converged_in_study(const ConvergenceRecord::Quantity& q) {
  if (!(std::isfinite(q.richardson) && std::isfinite(q.order) && q.order >= kMinimumObservedOrder)) return false;
  double finest_h = INFINITY, finest = NAN;
  for (const auto& [h, v] : q.levels)
    if (h < finest_h) finest_h = h, finest = v;
  return std::abs(finest / q.richardson - 1.0) <= kConvergedWithin;
}

JsonValue convergence_statement(const ConvergenceRecord& record, const std::string& fingerprint,
                                const std::string& configuration, double band_cell, const JsonValue& penetration,
                                bool patched) {
  JsonValue out = JsonValue::object();
  out["record"] = record.path;
  out["study"] = record.study;
  const bool matches = record.fingerprint == fingerprint;
  out["fingerprint_matches"] = matches;
  const ConvergenceRecord::Checked* checked = nullptr;
  for (const ConvergenceRecord::Checked& c : record.checked)
    if (c.fingerprint == configuration) {
      checked = &c;
      break;
    }
  // The configuration is the run only if the run reproduced what the record holds for it (the
  // fingerprint leaves out the end time and the build).
  for (std::size_t i = 0; checked && i < checked->values.size(); ++i) {
    const auto& [name, recorded] = checked->values[i];
    for (const ConvergenceRecord::Quantity& q : record.quantities) {
      if (q.name != name) continue;
      const JsonValue own = at_dotted(penetration, q.summary_key);
      if (own.kind() != JsonValue::Kind::Number ||
          !(std::abs(own.as_number() - recorded) <= kReproduced * std::abs(recorded))) {
        spdlog::warn("this run is the configuration '{}' of its grid study's record {} but did not reproduce its {} "
                     "({} against the recorded {}, beyond a build for another processor's 2 %: another end "
                     "time or code path): how far it is from converged is not known",
                     checked->name, record.path, q.label,
                     own.kind() == JsonValue::Kind::Number ? fmt::format("{:.9g}", own.as_number()) : "none",
                     recorded);
        checked = nullptr;
      }
      break;
    }
  }
  double level = NAN;
  for (const ConvergenceRecord::Quantity& q : record.quantities)
    for (const auto& [h, value] : q.levels)
      if (!patched && same_level(h, band_cell)) level = h;
  if (checked)
    ;  // the study ran this very configuration and the run reproduced it: nothing is unknown
  else if (!matches)
    spdlog::warn("the grid study's record {} is of other physics than this run (fingerprint {} against {}): how far "
                 "this run is from converged is not known (re-run validation/perforation_convergence.py for this deck)",
                 record.path, fingerprint, record.fingerprint);
  else if (patched)
    spdlog::warn("this run's grid has patches of finer cells (grid.patches), which its grid study ({}) did not "
                 "run: how far it is from converged is not known",
                 record.path);
  else if (!std::isfinite(level))
    spdlog::warn("this run's cells along the line of flight ({:.3g} m) are not a level of its grid study ({}): how "
                 "far it is from converged is not known",
                 band_cell, record.path);
  const bool at_level = !checked && matches && std::isfinite(level);
  out["level_cell"] = at_level ? JsonValue(level) : JsonValue();
  if (checked) {
    JsonValue c = JsonValue::object();
    c["name"] = checked->name;
    c["label"] = checked->label;
    out["checked"] = c;
  } else {
    out["checked"] = JsonValue();
  }
  JsonValue& qs = out["quantities"];
  qs = JsonValue::object();
  double within = 0.0;
  bool measured = false, all_converged = true, all_at_level = true;
  for (const ConvergenceRecord::Quantity& q : record.quantities) {
    JsonValue e = JsonValue::object();
    e["label"] = q.label;
    const bool converged = converged_in_study(q);
    all_converged = all_converged && converged;
    e["converged_in_study"] = converged;
    e["richardson"] = std::isfinite(q.richardson) ? JsonValue(q.richardson) : JsonValue();
    e["order"] = std::isfinite(q.order) ? JsonValue(q.order) : JsonValue();
    JsonValue value;
    if (at_level)
      for (const auto& [h, v] : q.levels)
        if (same_level(h, level)) value = JsonValue(v);
    if (checked)
      for (const auto& [name, v] : checked->values)
        if (name == q.name) value = JsonValue(v);
    e["level_value"] = value;
    all_at_level = all_at_level && value.kind() == JsonValue::Kind::Number;
    if (value.kind() == JsonValue::Kind::Number && converged) {
      const double gap = value.as_number() / q.richardson - 1.0;
      e["level_gap"] = gap;
      within = std::max(within, std::abs(gap));
      measured = true;
    } else {
      e["level_gap"] = JsonValue();
    }
    e["run_value"] = at_dotted(penetration, q.summary_key);
    qs[q.name] = e;
  }
  out["within"] = measured ? JsonValue(within) : JsonValue();
  out["all_converged"] = all_converged;
  out["all_at_level"] = (at_level || checked) && all_at_level;
  return out;
}

}  // namespace ballista
