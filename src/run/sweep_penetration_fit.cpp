#include "run/sweep_penetration_fit.hpp"

#include <cmath>
#include <iostream>
#include <set>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/python_tool.hpp"
#include "penetration/hydrodynamic.hpp"

namespace ballista {

namespace fs = std::filesystem;

namespace {

/// A finite number cell of the row's flattened summary, if present.
std::optional<double> number(const SweepRow& row, const std::string& column) {
  for (const auto& [name, cell] : row.scalars) {
    if (name != column || cell.kind != SweepCell::Kind::Number) continue;
    const double v = std::stod(cell.text);
    if (std::isfinite(v)) return v;
  }
  return std::nullopt;
}

/// A density cell, if present and positive (eq. 3.1 and 5.3-5.5 need rho > 0).
std::optional<double> density(const SweepRow& row, const std::string& column) {
  const auto v = number(row, column);
  return v && *v > 0 ? v : std::nullopt;
}

JsonValue json_of(const std::optional<double>& v) {
  return v ? JsonValue(*v) : JsonValue();
}

}  // namespace

std::optional<SweepPenetrationFit> sweep_penetration_fit(const SweepTable& table) {
  SweepPenetrationFit f;
  std::vector<double> V, U;
  for (const SweepRow& row : table.rows()) {
    if (row.status != "completed") continue;  // a failed run has no steady rate to fit
    const auto v = number(row, "penetration.impact_velocity"), u = number(row, "penetration.steady_rate");
    if (!v || !u) return std::nullopt;  // not an impact-velocity study (or a run without a steady state)
    SweepPenetrationPoint p;
    p.run = row.index;
    p.V = *v;
    p.U = *u;
    p.rho_p = density(row, "penetration.penetrator_density");
    p.rho_t = density(row, "penetration.target_density");
    if (p.rho_p && p.rho_t)
      p.U_h = penetration::hydrodynamic_penetration_velocity(p.V, *p.rho_p, *p.rho_t);  // eq. 3.1
    else
      p.U_h = number(row, "penetration.hydrodynamic_rate");  // as the run reported it
    f.points.push_back(p);
    V.push_back(p.V);
    U.push_back(p.U);
  }
  if (std::set<double>(V.begin(), V.end()).size() < 2) return std::nullopt;  // eq. 5.2 needs two velocities
  f.fit = penetration::fit_orphal_anderson(V, U);
  const double a = f.fit.a, b = f.fit.b;
  for (SweepPenetrationPoint& p : f.points)  // R - Y implied by the fitted line at each V, eq. 5.3
    if (p.rho_p && p.rho_t)
      p.R_minus_Y = penetration::orphal_anderson_strength_difference(a, b, *p.rho_p, *p.rho_t, p.V);

  // Eq. 5.4-5.5 are properties of the fitted line for one penetrator/target pair: only when every
  // run has the same densities.
  bool common = true;
  for (const SweepPenetrationPoint& p : f.points)
    common = common && p.rho_p && p.rho_t && *p.rho_p == *f.points.front().rho_p && *p.rho_t == *f.points.front().rho_t;
  if (common) {
    const double rp = *f.points.front().rho_p, rt = *f.points.front().rho_t;
    f.rho_p = rp;
    f.rho_t = rt;
    f.curvature = penetration::orphal_anderson_curvature(b, rp, rt);  // eq. 5.5
    f.hydrodynamic_slope = penetration::orphal_anderson_hydrodynamic_slope(rp, rt);
    // Eq. 5.5 is a difference of two terms; at the hydrodynamic slope it is zero up to the
    // round-off of the fitted b (relative 1e-12 of the terms), and V_m (eq. 5.4) would be a
    // meaningless 1e12-scale number: no extremum (R - Y linear in V).
    const double scale = rp * (b - 1) * (b - 1) + rt * b * b;
    if (std::abs(*f.curvature) > 1e-12 * scale)
      f.extremum_velocity = penetration::orphal_anderson_extremum_velocity(a, b, rp, rt);
  }
  return f;
}

JsonValue sweep_penetration_json(const SweepPenetrationFit& f) {
  JsonValue j = JsonValue::object();
  j["a"] = f.fit.a;
  j["b"] = f.fit.b;
  j["r2"] = f.fit.r2;
  j["penetrator_density"] = json_of(f.rho_p);
  j["target_density"] = json_of(f.rho_t);
  j["curvature"] = json_of(f.curvature);
  j["extremum_velocity"] = json_of(f.extremum_velocity);
  j["hydrodynamic_slope"] = json_of(f.hydrodynamic_slope);
  JsonValue& runs = j["runs"] = JsonValue::array();
  for (const SweepPenetrationPoint& p : f.points) {
    JsonValue r = JsonValue::object();
    r["run"] = p.run;
    r["V"] = p.V;
    r["U"] = p.U;
    r["U_h"] = json_of(p.U_h);
    r["U_over_Uh"] = p.U_h && *p.U_h != 0 ? JsonValue(p.U / *p.U_h) : JsonValue();
    r["R_minus_Y"] = json_of(p.R_minus_Y);
    runs.push_back(std::move(r));
  }
  return j;
}

bool write_sweep_penetration(const SweepTable& table, const fs::path& out_dir) {
  const auto f = sweep_penetration_fit(table);
  if (!f) return false;
  write_file_atomic((out_dir / "sweep_penetration.json").string(), sweep_penetration_json(*f).dump(2) + "\n");
  return true;
}

SweepPostStep sweep_penetration_post_step() {
  return [](const SweepTable& table, const fs::path& out_dir) {
    try {
      if (!write_sweep_penetration(table, out_dir)) return;
    } catch (const Error& e) {  // e.g. a non-finite V: the table is still complete
      std::cerr << "sweep: warning: U = a + bV fit not written: " << e.what() << "\n";
      return;
    }
    const std::string err =
        run_python_tool("plot_sweep_penetration.py", {out_dir.string()}, "the sweep penetration plot");
    if (!err.empty())
      std::cerr << "sweep: warning: penetration plots not written: " << err << "\n";
    else
      std::cout << "U = a + bV fit in " << fs::absolute(out_dir / "sweep_penetration.json").string() << "\n";
  };
}

}  // namespace ballista
