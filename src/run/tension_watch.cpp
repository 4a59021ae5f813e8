#include "run/tension_watch.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>

#include "core/point_fields.hpp"
#include "materials/cohesive_limit.hpp"

namespace ballista {

namespace {
// A point counts as beyond the limit once it is 0.1 % past it: a cutoff (eos.min_pressure) set at
// the limit as printed, to a few digits, holds its points at the limit, not beyond it.
constexpr double kMargin = 1e-3;
}  // namespace

TensionWatch::TensionWatch(const Scenario& sc) {
  slot_of_material_.assign(sc.materials.size(), -1);
  for (std::size_t m = 0; m < sc.materials.size(); ++m) {
    const ParamValues& v = sc.materials[m].params;
    if (v.choice("eos.type", "linear") != "mie_gruneisen" || !v.given("density")) continue;
    const Eos e = make_eos(v, 0.0, v.at("density"));
    const double limit = mie_gruneisen_cohesive_limit(e);
    // A cutoff at or above the limit keeps every point within it: nothing to watch.
    if (!std::isfinite(limit) || e.p_min >= limit * (1.0 + kMargin)) continue;
    Watched w;
    w.name = sc.materials[m].name;
    w.limit = limit;
    w.bulk = e.rho0 * e.c0 * e.c0;
    slot_of_material_[m] = static_cast<int>(watched_.size());
    watched_.push_back(w);
  }
}

void TensionWatch::scan(const FieldStore& pts, double time, const Communicator& comm) {
  if (watched_.empty()) return;
  const std::size_t n = watched_.size();
  std::vector<double> lowest(n, 0.0);
  std::vector<std::int64_t> beyond(n, 0);
  if (pts.size() > 0 && pts.has(kStress) && pts.has(kMaterialIndex)) {
    const Mat3* stress = pts.view(kStress);
    const std::int64_t* material = pts.ints(kMaterialIndex);
    for (Index p = 0; p < pts.size(); ++p) {
      const std::int64_t m = material[p];
      if (m < 0 || m >= static_cast<std::int64_t>(slot_of_material_.size())) continue;
      const int k = slot_of_material_[static_cast<std::size_t>(m)];
      if (k < 0) continue;
      const double pressure = -trace(stress[p]) / 3.0;  // tension negative
      if (pressure < lowest[k]) lowest[k] = pressure;
      if (pressure < watched_[k].limit * (1.0 + kMargin)) ++beyond[k];
    }
  }
  if (comm.distributed()) {
    for (double& l : lowest) l = comm.min(l);
    comm.sum(beyond.data(), static_cast<int>(n));
  }
  for (std::size_t k = 0; k < n; ++k) {
    Watched& w = watched_[k];
    if (lowest[k] < w.most_tensile) {
      w.most_tensile = lowest[k];
      w.most_tensile_time = time;
    }
    if (beyond[k] > w.most_beyond) {
      w.most_beyond = beyond[k];
      w.most_beyond_time = time;
    }
    if (beyond[k] > 0 && w.first_beyond_time < 0.0) {
      w.first_beyond_time = time;
      if (comm.rank() == 0)
        spdlog::warn(
            "{} points of material '{}' hold a hydrostatic tension beyond {:.3g} GPa at t = {:.6g} s (down to {:.3g} "
            "GPa): no solid of its bulk modulus ({:.3g} GPa) and Us-up slope holds that much (the cohesive limit of "
            "the universal equation of state, Vinet et al. 1987); the material would have parted there, and the "
            "results near those points are not physical (eos.min_pressure caps the tension; summary.json "
            "\"tension\" has the record)",
            beyond[k], w.name, w.limit * 1e-9, time, lowest[k] * 1e-9, w.bulk * 1e-9);
    }
  }
}

JsonValue TensionWatch::summary() const {
  JsonValue out = JsonValue::object();
  const auto time_or_null = [](double t) { return t >= 0.0 ? JsonValue(t) : JsonValue(); };
  for (const Watched& w : watched_) {
    JsonValue& m = out[w.name];
    m = JsonValue::object();
    m["cohesive_limit"] = w.limit;
    m["most_tensile_pressure"] = w.most_tensile;
    m["most_tensile_time"] = time_or_null(w.most_tensile_time);
    m["most_points_beyond"] = static_cast<double>(w.most_beyond);
    m["most_points_beyond_time"] = time_or_null(w.most_beyond_time);
    m["first_beyond_time"] = time_or_null(w.first_beyond_time);
  }
  return out;
}

void TensionWatch::save(StateArchive& a) const {
  std::vector<double> reals;
  for (const Watched& w : watched_)
    reals.insert(reals.end(), {w.most_tensile, w.most_tensile_time, static_cast<double>(w.most_beyond),
                               w.most_beyond_time, w.first_beyond_time});
  a.put("run.tension_watch", reals);
}

void TensionWatch::load(const StateArchive& a) {
  if (!a.has("run.tension_watch")) return;
  const std::vector<double>& v = a.reals("run.tension_watch");
  if (v.size() != 5 * watched_.size()) return;  // another deck's materials: the record starts afresh
  for (std::size_t k = 0; k < watched_.size(); ++k) {
    Watched& w = watched_[k];
    w.most_tensile = v[5 * k];
    w.most_tensile_time = v[5 * k + 1];
    w.most_beyond = static_cast<std::int64_t>(v[5 * k + 2]);
    w.most_beyond_time = v[5 * k + 3];
    w.first_beyond_time = v[5 * k + 4];
  }
}

}  // namespace ballista
