#include "run/particle_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "core/point_fields.hpp"
#include "driver/drive_history.hpp"
#include "driver/ftable_csv.hpp"
#include "materials/material.hpp"

namespace ballista {

ParticleTracker::ParticleTracker(const Scenario& sc, const std::string& out_dir, std::int64_t total_ids)
    : dir_((std::filesystem::path(out_dir) / "tracks").string()), ids_(sc.output.track) {
  for (std::int64_t id : ids_)
    if (id < 0 || id >= total_ids)
      throw DeckError(sc.output.track_mark.file, sc.output.track_mark.line, sc.output.track_mark.column,
                      "output.track.ids",
                      "no particle with id " + std::to_string(id) + " (this deck seeds " + std::to_string(total_ids) +
                          " particles, ids 0.." + std::to_string(total_ids - 1) + ")");
  for (const auto& m : sc.materials) {
    std::vector<std::string> names;
    // The instance's fields (they depend on the parameters, e.g. backstress only with kinematic
    // hardening, damage only with a failure criterion), not the registry's full list.
    if (const MaterialFactory* f = find_material(m.model))
      for (const auto& s : f->create(m.name, m.params)->state_fields()) names.push_back(s.name);
    state_names_.push_back(names);
  }
  if (!ids_.empty()) std::filesystem::create_directories(dir_);
}

void ParticleTracker::locate(const FieldStore& points) {
  where_.assign(ids_.size(), -1);
  const auto* id = points.ints(kId);
  for (Index p = 0; p < points.size(); ++p)
    for (size_t k = 0; k < ids_.size(); ++k)
      if (id[p] == ids_[k]) where_[k] = p;
}

void ParticleTracker::open(std::int64_t id, int material, const long long* resume_bytes) {
  Track& t = tracks_[id];
  t.material = material;
  const std::string stem = (std::filesystem::path(dir_) / ("particle_" + std::to_string(id))).string();
  t.table = resume_bytes ? std::make_unique<HistoryWriter>(stem + ".csv", ftable_columns(false), resume_bytes[0])
                         : std::make_unique<HistoryWriter>(stem + ".csv", ftable_columns(false));
  // The driver's columns without those the solver does not have (per-step plastic work density,
  // Newton iterations).
  std::vector<std::string> cols;
  for (const auto& c : drive_history_columns(state_names_.at(material))) {
    const bool keep = c != "plastic_work" && c != "iterations";
    t.keep.push_back(keep);
    if (keep) cols.push_back(c);
  }
  t.history = resume_bytes ? std::make_unique<HistoryWriter>(stem + "_history.csv", cols, resume_bytes[1])
                           : std::make_unique<HistoryWriter>(stem + "_history.csv", cols);
}

void ParticleTracker::record(const FieldStore& points, double t, long step) {
  if (ids_.empty()) return;
  locate(points);
  const auto* F = points.view(kDeformationGradient);
  const auto* R = points.view(kRotation);
  const auto* stress = points.view(kStress);
  const auto* mat = points.ints(kMaterialIndex);
  const auto* vol0 = points.real(kReferenceVolume);
  const auto* wp = points.real(kPlasticWork);
  const auto* eint = points.real(kInternalEnergy);
  for (size_t k = 0; k < ids_.size(); ++k) {
    const Index p = where_[k];
    if (p < 0) continue;
    const std::int64_t id = ids_[k];
    const int m = static_cast<int>(mat[p]);
    if (!tracks_.count(id)) open(id, m);
    Track& tr = tracks_[id];
    if (!tr.started && step > 0) {
      // First seen after a step (a body activated during it): its table starts at the step's
      // beginning with the F it was seeded with (activated bodies start undeformed).
      tr.table->row({t_prev_, 1, 0, 0, 0, 1, 0, 0, 0, 1});
    }
    tr.started = true;
    std::vector<double> frow = {t};
    frow.insert(frow.end(), F[p].a, F[p].a + 9);
    tr.table->row(frow);
    DriveRecord rec;
    rec.t = t;
    rec.step = step;
    rec.F = F[p];
    rec.R = R[p];
    rec.sigma = stress[p];
    rec.sigma_bar = unrotate_sym(R[p], stress[p]);
    for (const auto& s : state_names_.at(m)) rec.state.push_back(points.real(s)[p]);
    rec.plastic_work_total = wp[p] / vol0[p];  // J -> J per m^3 of reference volume
    rec.internal_energy = eint[p] / vol0[p];
    const std::vector<double> full = drive_history_row(rec);
    std::vector<double> row;
    for (size_t c = 0; c < full.size(); ++c)
      if (tr.keep[c]) row.push_back(full[c]);
    tr.history->row(row);
  }
  t_prev_ = t;
}

void ParticleTracker::record_failure(const FieldStore& points, double t) {
  if (ids_.empty()) return;
  locate(points);
  const auto* F = points.view(kDeformationGradient);
  for (size_t k = 0; k < ids_.size(); ++k) {
    auto it = tracks_.find(ids_[k]);
    if (where_[k] < 0 || it == tracks_.end()) continue;
    std::vector<double> frow = {t};
    frow.insert(frow.end(), F[where_[k]].a, F[where_[k]].a + 9);
    it->second.table->row(frow);
  }
}

ParticleTracker::State ParticleTracker::state() const {
  State s;
  s.t_prev = t_prev_;
  for (const auto& [id, t] : tracks_)
    s.tracks.insert(s.tracks.end(), {id, t.material, t.started ? 1 : 0, t.table->bytes(), t.history->bytes()});
  return s;
}

void ParticleTracker::save_state(StateArchive& a, const State& s) const {
  a.put("tracks.ids", ids_);
  a.put("tracks.open", s.tracks);
  a.put_real("tracks.t_prev", s.t_prev);
}

void ParticleTracker::load_state(const StateArchive& a) {
  // A track added now would start in the middle of the run: its F-table would miss the steps
  // before, and a replay of it would be wrong.
  const auto& saved = a.ints("tracks.ids");
  for (std::int64_t id : ids_)
    if (std::find(saved.begin(), saved.end(), id) == saved.end())
      throw Error("output.track.ids adds particle " + std::to_string(id) +
                  " at a restart: its F-table would miss the steps before the checkpoint; run the deck from the "
                  "start to track it");
  const auto& v = a.ints("tracks.open");
  t_prev_ = a.real("tracks.t_prev");
  tracks_.clear();
  for (std::size_t k = 0; k + 5 <= v.size(); k += 5) {
    if (std::find(ids_.begin(), ids_.end(), v[k]) == ids_.end())
      throw Error("the checkpoint tracks particle " + std::to_string(v[k]) +
                  ", which output.track.ids no longer names; restart with the same ids");
    const long long bytes[2] = {v[k + 3], v[k + 4]};
    open(v[k], static_cast<int>(v[k + 1]), bytes);
    tracks_[v[k]].started = v[k + 2] != 0;
  }
}

}  // namespace ballista
