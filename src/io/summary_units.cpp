#include "io/summary_units.hpp"

#include <utility>
#include <vector>

namespace ballista {

namespace {

/// Patterns of summary.json paths and their units, first match wins. '*' stands for one
/// component whatever its name (a layer, a deleted body, a solver's result). Totals of extensive
/// quantities are of the whole body (docs/output.md, Conventions).
const std::vector<std::pair<std::string, std::string>>& unit_table() {
  static const std::vector<std::pair<std::string, std::string>> table = {
      {"main_stage_start", "s"},
      {"failed_step", "1"},
      {"failed_particle", "1"},
      {"tracked_particles[]", "1"},
      {"stages[].start_time", "s"},
      {"stages[].end_time", "s"},
      {"stages[].damping", "1/s"},
      {"stages[].worst_deviation", "1"},
      {"stages[].worst_particle", "1"},
      {"stages[].fraction_within", "1"},
      // The penetration analysis (docs/penetration.md).
      {"penetration.impact_velocity", "m/s"},
      {"penetration.penetrator_density", "kg/m^3"},
      {"penetration.target_density", "kg/m^3"},
      {"penetration.segments", "1"},
      {"penetration.arrival_time", "s"},
      {"penetration.stop_time", "s"},
      {"penetration.end_when_spent.share", "1"},
      {"penetration.end_when_spent.time", "s"},
      {"penetration.steady_rate", "m/s"},
      {"penetration.hydrodynamic_rate", "m/s"},
      {"penetration.rate_over_hydrodynamic", "1"},
      {"penetration.cells_across_radius", "1"},
      {"penetration.steady_fit.intercept", "m"},
      {"penetration.steady_fit.t_begin", "s"},
      {"penetration.steady_fit.t_end", "s"},
      {"penetration.steady_fit.r2", "1"},
      {"penetration.steady_fit.points", "1"},
      {"penetration.analytic[].depth", "m"},
      {"penetration.holes.*.jet_behind.time", "s"},
      {"penetration.holes.*.jet_behind.tip_velocity", "m/s"},
      {"penetration.holes.*.jet_behind.tip_initial_velocity", "m/s"},
      {"penetration.holes.*.jet_behind.tip_segment", "1"},
      {"penetration.holes.*.jet_behind.*", "m"},  // the lengths consumed and remaining
      {"penetration.holes.*.*", "m"},             // diameters, thickness, face depth
      {"penetration.tunnel.*", "m"},
      {"penetration.convergence.quantities.*.order", "1"},
      {"penetration.convergence.quantities.*.level_gap", "1"},
      {"penetration.convergence.quantities.*.*", "m"},  // the study's quantities are lengths
      {"penetration.convergence.within", "1"},
      {"penetration.convergence.level_cell", "m"},
      {"penetration.beyond_tunnel.points", "1"},
      {"penetration.beyond_tunnel.mass_share", "1"},
      {"penetration.beyond_tunnel.*", "m"},  // the tunnel's end, the margin, the deepest point
      {"penetration.path_cells.*", "m"},  // cell sizes and the depth they coarsen from
      {"penetration.*", "m"},  // depths, lengths, radii, the surface's coordinate
      // Fragments (the Mott fit N(>m) = N0 exp(-sqrt(m / mu))).
      {"fragments.time", "s"},
      {"fragments.above_min_mass.count", "1"},
      {"fragments.above_min_mass.mott_N0", "1"},
      {"fragments.above_min_mass.mott_r2", "1"},
      {"fragments.above_min_mass.*", "kg"},
      {"fragments.count", "1"},
      {"fragments.mott_N0", "1"},
      {"fragments.mott_r2", "1"},
      {"fragments.*", "kg"},  // largest, mean, total masses and mu
      // What the solvers report (src/*/..._solver.cpp result_values).
      {"solver_results.largest_fragment_mass", "kg"},
      {"solver_results.mean_fragment_mass", "kg"},
      {"solver_results.bytes_per_bond_end", "B"},
      {"solver_results.momentum_change_x", "kg m/s"},
      {"solver_results.momentum_change_y", "kg m/s"},
      {"solver_results.momentum_change_z", "kg m/s"},
      {"solver_results.*", "1"},  // counts, the largest damage, the LME condition numbers
      {"timing.*", "s"},
      {"statistics.end_time", "s"},
      {"statistics.wall_time", "s"},
      {"statistics.min_dt", "s"},
      {"statistics.particle_steps_per_second", "1/s"},
      {"statistics.min_dt_set_by.time", "s"},
      {"statistics.min_dt_set_by.dt", "s"},
      {"statistics.min_dt_set_by.wave_speed", "m/s"},
      {"statistics.min_dt_set_by.speed", "m/s"},
      {"statistics.min_dt_set_by.cell", "m"},
      {"statistics.min_dt_set_by.*", "1"},  // the particle's id, its J
      {"statistics.step_set_by.entries[].signal_speed_max", "m/s"},
      {"statistics.step_set_by.*", "1"},    // the interval and the sample counts
      {"statistics.step_set_by.entries[].*", "1"},  // shares, counts, J, the margin
      {"statistics.*", "1"},                // counts, the worst energy drift (over the scale)
      // Points beyond their material's cohesive limit (run/tension_watch.hpp), per material.
      {"tension.*.cohesive_limit", "Pa"},
      {"tension.*.most_tensile_pressure", "Pa"},
      {"tension.*.most_tensile_time", "s"},
      {"tension.*.most_points_beyond", "1"},
      {"tension.*.most_points_beyond_time", "s"},
      {"tension.*.first_beyond_time", "s"},
      {"deleted.*.mass", "kg"},
      {"deleted.*.energy", "J"},
      {"deleted.*.*", "1"},  // points, mass fraction
      {"energy.mass", "kg"},
      {"energy.removed_mass", "kg"},
      {"energy.residual_over_scale", "1"},
      {"energy.*", "J"},
  };
  return table;
}

std::vector<std::string> components(const std::string& path) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (true) {
    const std::size_t dot = path.find('.', at);
    out.push_back(path.substr(at, dot - at));
    if (dot == std::string::npos) return out;
    at = dot + 1;
  }
}

bool matches(const std::vector<std::string>& pattern, const std::vector<std::string>& path) {
  if (pattern.size() != path.size()) return false;
  for (std::size_t k = 0; k < path.size(); ++k)
    if (pattern[k] != "*" && pattern[k] != path[k]) return false;
  return true;
}

void collect(const JsonValue& v, const std::string& path, const std::map<std::string, std::string>& probe_units,
             JsonValue& out) {
  switch (v.kind()) {
    case JsonValue::Kind::Object:
      for (const std::string& key : v.keys()) collect(v.at(key), path.empty() ? key : path + "." + key, probe_units, out);
      return;
    case JsonValue::Kind::Array:
      for (std::size_t k = 0; k < v.size(); ++k) collect(v.at(k), path + "[]", probe_units, out);
      return;
    case JsonValue::Kind::Int:
    case JsonValue::Kind::Number: {
      std::string unit;
      if (path.rfind("probes.", 0) == 0) {
        const auto it = probe_units.find(path.substr(7));
        if (it != probe_units.end()) unit = it->second;
      } else {
        unit = summary_unit(path);
      }
      if (!unit.empty() && !out.contains(path)) out[path] = unit;
      return;
    }
    default: return;
  }
}

}  // namespace

std::string summary_unit(const std::string& path) {
  const std::vector<std::string> p = components(path);
  for (const auto& [pattern, unit] : unit_table())
    if (matches(components(pattern), p)) return unit;
  return "";
}

JsonValue summary_units(const JsonValue& root, const std::map<std::string, std::string>& probe_units) {
  JsonValue out = JsonValue::object();
  collect(root, "", probe_units, out);
  return out;
}

}  // namespace ballista
