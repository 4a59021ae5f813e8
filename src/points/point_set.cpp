#include "points/point_set.hpp"
#include "points/point_exchange.hpp"
#include "points/body_overlap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <numeric>
#include <sstream>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "core/system_memory.hpp"
#include "geometry/seeding.hpp"
#include "materials/explosive_eos.hpp"
#include "materials/failure.hpp"
#include "points/explosive_lighting.hpp"
#include "points/initial_state_registry.hpp"
#include "points/prestress.hpp"
#include "points/load_registry.hpp"

namespace ballista {

PointSet::PointSet(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials, const SeedLattice& lattice,
                   double solver_bytes, const std::string& memory_what, Communicator comm)
    : scenario_(sc), materials_(std::move(materials)), comm_(comm) {
  const Dimension dim = sc.simulation.dimension;
  GridSpec grid = lattice.box;
  // Points: common fields, then every material's state fields.
  declare_point_fields(points_);
  for (const auto& m : materials_) m->declare_fields(points_);

  // Refuse a run that cannot fit before allocating it (rather than die in a bare std::bad_alloc).
  // Per point: every declared field plus a solver's per-point scratch (~3 Vec3 and 5 indices). The
  // point count is the bodies' bounding-box lattice, an upper bound.
  {
    const double bytes_per_point =
        points_.bytes_per_point() + 3 * sizeof(Vec3) + 5 * sizeof(Index) + lattice.solver_bytes_per_point;
    double npoints = 0.0;
    for (BodySpec body : sc.bodies) {
      if (lattice.override_ppc > 0) body.particles_per_cell = lattice.override_ppc;
      npoints += lattice_point_bound(body, grid, dim);
    }
    require_memory(solver_bytes + npoints * bytes_per_point,
                   fmt::format("{}up to {:.3g} points x {:g} B", memory_what.empty() ? "" : memory_what + " + ",
                               npoints, bytes_per_point),
                   sc.file, "grid.cell_size");
  }

  std::int64_t next_id = 0;
  std::vector<double> activation;
  std::vector<int> activation_stage;
  for (size_t b = 0; b < sc.bodies.size(); ++b) {
    BodySpec body = sc.bodies[b];
    if (lattice.override_ppc > 0) body.particles_per_cell = lattice.override_ppc;
    int mi = -1;
    for (size_t m = 0; m < materials_.size(); ++m)
      if (materials_[m]->name() == body.material) mi = static_cast<int>(m);
    if (mi < 0)
      throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path + ".material",
                      "unknown material '" + body.material + "'");
    const Index n0 = points_.size();
    if (body.segments.empty()) {
      seed_body(body, static_cast<int>(b), mi, *materials_[mi], grid, dim, points_, next_id);
      activation.resize(points_.size(), body.activation_time);
    } else {
      // Rods and jets: each segment with its own shape, velocity and activation time.
      for (size_t k = 0; k < body.segments.size(); ++k) {
        BodySpec piece = body;
        piece.shape = body.segments[k].shape;
        piece.velocity = body.segments[k].velocity;
        const Index s0 = points_.size();
        seed_body(piece, static_cast<int>(b), mi, *materials_[mi], grid, dim, points_, next_id);
        auto* seg = points_.ints(kSegment);
        for (Index p = s0; p < points_.size(); ++p) seg[p] = static_cast<int>(k);
        activation.resize(points_.size(), body.segments[k].activation_time);
      }
    }
    activation_stage.resize(points_.size(), body.activation_stage);
    materials_[mi]->initialise_state(points_, n0, points_.size());
    if (const InitialStateFactory* state = find_initial_state(body.initial_state))
      state->apply(body, *materials_[mi], points_, n0, points_.size());
    if (body.prestress) {
      try {
        apply_prestress(*materials_[mi], *body.prestress, dim, points_, n0, points_.size());
      } catch (const std::runtime_error& e) {
        throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path,
                        "body '" + body.name + "' (prestressed by its confinement load): " + e.what());
      }
    }
  }
  check_body_overlaps(sc, points_);
  {
    const std::size_t nb = sc.bodies.size();
    seeded_mass_body_.assign(nb, 0.0);
    removed_points_body_.assign(nb, 0.0);
    removed_mass_body_.assign(nb, 0.0);
    removed_energy_body_.assign(nb, 0.0);
    const auto* body = points_.ints(kBodyIndex);
    const auto* mass = points_.real(kMass);
    for (Index p = 0; p < points_.size(); ++p) seeded_mass_body_[static_cast<std::size_t>(body[p])] += mass[p];
  }
  // Loads that act on marked points (a pressure's loaded surface) mark them now, on the seeding.
  for (size_t k = 0; k < sc.loads.size(); ++k) {
    const LoadSpec& load = sc.loads[k];
    const LoadFactory* kind = find_load(load.type);
    if (!kind || !kind->mark) continue;
    const int bi = body_index(sc, load.body);
    BodySpec body = sc.bodies.at(bi);
    if (lattice.override_ppc > 0) body.particles_per_cell = lattice.override_ppc;
    for (std::string& f : kind->mark(load, static_cast<int>(k), {body, bi, grid.cell_size, dim}, points_))
      load_area_fields_.push_back(std::move(f));
  }
  // Program burn: the lighting times of the explosive points, before any body waits for activation.
  light_explosives(sc, points_, lattice.override_ppc);
  // Bodies with a later activation time wait in pending_.
  std::vector<Index> later;
  std::vector<char> keep(points_.size(), 1);
  stage_start_.assign(sc.stages.size() + 1, std::numeric_limits<double>::infinity());
  stage_start_[0] = 0.0;
  for (Index p = 0; p < points_.size(); ++p)
    if (activation[p] > 0.0 || activation_stage[p] > 0) {
      later.push_back(p);
      keep[p] = 0;
      pending_activation_.push_back(activation[p]);
      pending_stage_.push_back(activation_stage[p]);
    }
  pending_ = points_.empty_like();
  if (!later.empty()) {
    pending_.append_from(points_, later);
    points_.compact(keep);
  }
}

void PointSet::keep_share(const Communicator& comm) {
  if (!comm.distributed()) return;
  auto range = [&](Index n) {
    return std::pair<Index, Index>{n * comm.rank() / comm.size(), n * (comm.rank() + 1) / comm.size()};
  };
  const auto [lo, hi] = range(points_.size());
  const auto [plo, phi] = range(pending_.size());
  keep_ranges(lo, hi, plo, phi);
}

void PointSet::keep(const std::vector<char>& keep) {
  if (pending_.size() > 0) throw Error("PointSet::keep: pending points are not supported");
  points_.compact(keep);
  groups_dirty_ = true;
}

void PointSet::keep_share(const Communicator& comm, const std::vector<char>& keep) {
  if (!comm.distributed()) return;
  const Index np = pending_.size();
  keep_with_pending(keep, np * comm.rank() / comm.size(), np * (comm.rank() + 1) / comm.size());
}

void PointSet::keep_ranges(Index first, Index last, Index first_pending, Index last_pending) {
  std::vector<char> keep(static_cast<std::size_t>(points_.size()), 0);
  std::fill(keep.begin() + first, keep.begin() + last, 1);
  keep_with_pending(std::move(keep), first_pending, last_pending);
}

void PointSet::keep_with_pending(std::vector<char> keep, Index first_pending, Index last_pending) {
  points_.compact(keep);
  keep.assign(static_cast<std::size_t>(pending_.size()), 0);
  std::fill(keep.begin() + first_pending, keep.begin() + last_pending, 1);
  pending_.compact(keep);
  pending_activation_ = std::vector<double>(pending_activation_.begin() + first_pending,
                                            pending_activation_.begin() + last_pending);
  pending_stage_ = std::vector<int>(pending_stage_.begin() + first_pending, pending_stage_.begin() + last_pending);
  groups_dirty_ = true;
}

void PointSet::begin_stage(int stage, double time) {
  if (stage < 0 || stage >= static_cast<int>(stage_start_.size()))
    throw Error("stage index " + std::to_string(stage) + " out of range");
  stage_start_[stage] = time;
}

bool PointSet::activate(double time) {
  if (pending_.size() == 0) return false;
  std::vector<Index> now;
  std::vector<char> keep(pending_.size(), 1);
  std::vector<double> still;
  std::vector<int> still_stage;
  for (Index p = 0; p < pending_.size(); ++p) {
    // Activation times count from the start of the body's activation stage (infinite until then).
    if (activation_time(p) <= time) {
      now.push_back(p);
      keep[p] = 0;
    } else {
      still.push_back(pending_activation_[p]);
      still_stage.push_back(pending_stage_[p]);
    }
  }
  if (now.empty()) return false;
  // Their kinetic and internal energy enters the energy balance as work done from outside (a
  // jet segment inserted at its velocity, thesis seed 000 §5.1), so the drift stays meaningful.
  {
    const auto* v = pending_.view(kVelocity);
    const auto* m = pending_.real(kMass);
    const auto* e = pending_.real(kInternalEnergy);
    for (Index p : now) inserted_energy_ += 0.5 * m[p] * dot(v[p], v[p]) + e[p];
  }
  points_.append_from(pending_, now);
  pending_.compact(keep);
  groups_dirty_ = true;
  pending_activation_.swap(still);
  pending_stage_.swap(still_stage);
  return true;
}

double PointSet::next_activation(double time) const {
  double next = std::numeric_limits<double>::infinity();
  for (Index p = 0; p < pending_.size(); ++p) {
    const double t = activation_time(p);
    if (t > time) next = std::min(next, t);
  }
  return next;
}

bool PointSet::activation_due(double time) const {
  for (Index p = 0; p < pending_.size(); ++p)
    if (activation_time(p) <= time) return true;
  return false;
}

const std::vector<std::vector<Index>>& PointSet::material_groups() {
  if (!groups_dirty_) return material_points_;
  material_points_.resize(materials_.size());
  for (auto& list : material_points_) list.clear();  // keeps capacity: no allocation per sort
  const auto* mat = points_.ints(kMaterialIndex);
  for (Index p = 0; p < points_.size(); ++p) material_points_[mat[p]].push_back(p);
  groups_dirty_ = false;
  return material_points_;
}

double PointSet::max_signal_speed() {
  const auto& groups = material_groups();
  double local_max = 0.0;
  for (size_t m = 0; m < materials_.size(); ++m)
    local_max = std::max(local_max, materials_[m]->max_signal_speed(points_, groups[m].data(),
                                                                    static_cast<Index>(groups[m].size())));
  return local_max;
}

void PointSet::zero_wave_speeds_of_stress_free(double* c) const {
  if (!points_.has(kFailed)) return;
  std::vector<char> stress_free(materials_.size(), 0);
  bool any = false;
  for (std::size_t m = 0; m < materials_.size(); ++m) any |= (stress_free[m] = materials_[m]->failed_points_are_stress_free());
  if (!any) return;
  const auto* failed = points_.real(kFailed);
  const auto* mat = points_.ints(kMaterialIndex);
  const Index n = points_.size();
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p)
    if (failed[p] > 0.0 && stress_free[static_cast<std::size_t>(mat[p])]) c[p] = 0.0;
}

StepLimiter PointSet::step_limiter() const {
  StepLimiter out;
  const auto* id = points_.ints(kId);
  const auto* bid = points_.ints(kBodyIndex);
  const auto* mat = points_.ints(kMaterialIndex);
  const auto* v = points_.view(kVelocity);
  const auto* F = points_.view(kDeformationGradient);
  double best = -1.0;
  for (Index p = 0; p < points_.size(); ++p) {
    const double J = det(F[p]);
    const double c = materials_[mat[p]]->wave_speed(points_, p, J);
    const double s = norm(v[p]);
    if (c + s > best) {
      best = c + s;
      out = {id[p], static_cast<int>(bid[p]), c, s, J};
    }
  }
  if (!comm_.distributed()) return out;
  const int root = comm_.rank_of_max(out.id >= 0 ? out.wave_speed + out.speed : -1.0);
  comm_.broadcast(&out, sizeof out, root);
  return out;
}

void PointSet::update_stress(double dt, long step, double time, const std::vector<std::uint8_t>& only, Index begin,
                             Index end) {
  const Index n = points_.size();
  if (end < 0) end = n;
  const auto& groups = material_groups();
  std::atomic<Index> bad_stress{n};
  std::atomic<Index> remaps{0};
  for (size_t m = 0; m < materials_.size(); ++m) {
    if (groups[m].empty() || (!only.empty() && !only[m])) continue;
    const std::span<const Index> in = material_points_in(m, begin, end);
    if (in.empty()) continue;
    MaterialBatch b = make_batch(points_, in.data(), static_cast<Index>(in.size()), dt, true);
    b.first_bad = &bad_stress;
    b.time = time;
    b.distortion_limit = distortion_limit_;
    b.distortion_remaps = &remaps;
    materials_[m]->update(b);
  }
  distortion_remaps_ += remaps.load();
  if (bad_stress.load() < n) fail(bad_stress.load(), "non-finite stress after the material update", step, time);
}

std::int64_t PointSet::distortion_remaps() const { return comm_.sum(distortion_remaps_); }
std::int64_t PointSet::frozen_increments_discarded() const { return comm_.sum(frozen_discarded_); }

bool PointSet::failed_stress_free(Index p) const {
  if (!points_.has(kFailed) || points_.real(kFailed)[p] == 0.0) return false;
  return materials_[static_cast<std::size_t>(points_.ints(kMaterialIndex)[p])]->failed_points_are_stress_free();
}

void PointSet::remove(const std::vector<char>& keep) {
  const Index n = points_.size();
  const auto* v = points_.view(kVelocity);
  const auto* mass = points_.real(kMass);
  const auto* eint = points_.real(kInternalEnergy);
  const double* chem = points_.has(kChemicalEnergy) ? points_.real(kChemicalEnergy) : nullptr;
  const auto* vol0 = points_.real(kReferenceVolume);
  const auto* body = points_.ints(kBodyIndex);
  for (Index p = 0; p < n; ++p) {
    if (keep[p]) continue;
    const double energy = 0.5 * mass[p] * dot(v[p], v[p]) + eint[p];
    removed_mass_ += mass[p];
    removed_momentum_ += mass[p] * v[p];
    removed_energy_ += energy;
    if (chem) removed_chemical_ += chem[p] * vol0[p];
    const std::size_t b = static_cast<std::size_t>(body[p]);
    removed_points_body_[b] += 1.0;
    removed_mass_body_[b] += mass[p];
    removed_energy_body_[b] += energy;
  }
  points_.compact(keep);
  groups_dirty_ = true;
}

void PointSet::book_vented(Index p) {
  const Vec3& v = points_.view(kVelocity)[p];
  const double m = points_.real(kMass)[p];
  removed_momentum_ += m * v;
  removed_energy_ += 0.5 * m * dot(v, v) + points_.real(kInternalEnergy)[p];
}

void PointSet::fail(Index p, const std::string& what, long step, double time) const {
  std::ostringstream os;
  os.precision(6);
  const auto* id = points_.ints(kId);
  const auto* bid = points_.ints(kBodyIndex);
  const Vec3& x = points_.view(kPosition)[p];
  const Mat3& F = points_.view(kDeformationGradient)[p];
  const Mat3& s = points_.view(kStress)[p];
  os << "particle " << id[p] << " of body '" << scenario_.bodies.at(bid[p]).name << "' " << what << " at step "
     << step << " (t = " << time << " s)\n"
     << "  position [" << x[0] << ", " << x[1] << ", " << x[2] << "] m";
  // A solver whose points carry no deformation gradient (peridynamic bonds) has cleared F's output.
  if (!points_.info(kDeformationGradient).output) throw ParticleError(id[p], os.str());
  os << "\n  F = [" << F(0, 0) << " " << F(0, 1) << " " << F(0, 2) << "; " << F(1, 0) << " " << F(1, 1) << " "
     << F(1, 2) << "; " << F(2, 0) << " " << F(2, 1) << " " << F(2, 2) << "], J = " << det(F) << "\n  stress = ["
     << s(0, 0) << " " << s(0, 1) << " " << s(0, 2) << "; " << s(1, 0) << " " << s(1, 1) << " " << s(1, 2) << "; "
     << s(2, 0) << " " << s(2, 1) << " " << s(2, 2) << "] Pa";
  throw ParticleError(id[p], os.str());
}

EnergyTotals PointSet::energies(double k, double external_work) const {
  const auto* v = points_.view(kVelocity);
  const auto* mass = points_.real(kMass);
  const auto* eint = points_.real(kInternalEnergy);
  const auto* wp = points_.real(kPlasticWork);
  // Failed (eroded) points keep the internal energy they had when their stress was zeroed.
  const double* failed = points_.has(kFailed) ? points_.real(kFailed) : nullptr;
  // Explosives (materials/explosive.cpp): the chemical energy released, J/m^3 of initial volume.
  const double* chem = points_.has(kChemicalEnergy) ? points_.real(kChemicalEnergy) : nullptr;
  const auto* vol0 = points_.real(kReferenceVolume);
  double s[9];
  deterministic_sum<9>(0, points_.size(), [&](Index p, double* o) {
    const double m = mass[p];
    o[0] += 0.5 * m * dot(v[p], v[p]);
    o[1] += eint[p];
    o[2] += wp[p];
    o[3] += m;
    o[4] += m * v[p][0];
    o[5] += m * v[p][1];
    o[6] += m * v[p][2];
    if (failed && failed[p] > 0.0) o[7] += eint[p];
    if (chem) o[8] += chem[p] * vol0[p];
  }, s);
  comm_.sum(s, 9);
  EnergyTotals e;
  e.kinetic = k * s[0];
  e.internal = k * s[1];
  e.plastic = k * s[2];
  e.eroded = k * s[7];
  e.mass = k * s[3];
  // Axisymmetric: only the axial momentum of a body of revolution is non-zero in total.
  e.momentum = Vec3{{scenario_.simulation.dimension == Dimension::Axisymmetric ? 0.0 : k * s[4], k * s[5], k * s[6]}};
  e.external = k * external_work;
  double removed[5] = {removed_mass_, removed_energy_, removed_momentum_[0], removed_momentum_[1],
                       removed_momentum_[2]};
  comm_.sum(removed, 5);
  e.removed_mass = k * removed[0];
  e.removed_energy = k * removed[1];
  e.removed_momentum = k * Vec3{{removed[2], removed[3], removed[4]}};
  e.inserted_energy = k * comm_.sum(inserted_energy_);
  e.chemical = k * (s[8] + comm_.sum(removed_chemical_));
  const std::size_t nb = removed_points_body_.size();
  std::vector<double> by_body = removed_points_body_;
  by_body.insert(by_body.end(), removed_mass_body_.begin(), removed_mass_body_.end());
  by_body.insert(by_body.end(), removed_energy_body_.begin(), removed_energy_body_.end());
  comm_.sum(by_body.data(), static_cast<int>(by_body.size()));
  e.removed_points_by_body.assign(by_body.begin(), by_body.begin() + nb);
  for (std::size_t b = 0; b < nb; ++b) {
    e.removed_mass_by_body.push_back(k * by_body[nb + b]);
    e.removed_energy_by_body.push_back(k * by_body[2 * nb + b]);
    e.seeded_mass_by_body.push_back(k * seeded_mass_body_[b]);
  }
  return e;
}

}  // namespace ballista

namespace ballista {

/// Entries of the removal record before the per-body ones (all that older checkpoints hold).
constexpr std::size_t kRemovalTotals = 7;

std::vector<double> PointSet::removal_record() const {
  std::vector<double> r{removed_mass_,        removed_energy_,       removed_chemical_, removed_momentum_[0],
                        removed_momentum_[1], removed_momentum_[2], inserted_energy_};
  r.insert(r.end(), removed_points_body_.begin(), removed_points_body_.end());
  r.insert(r.end(), removed_mass_body_.begin(), removed_mass_body_.end());
  r.insert(r.end(), removed_energy_body_.begin(), removed_energy_body_.end());
  return r;
}

namespace {

/// What a checkpoint holds of the points, the same on one rank and (gathered) on several.
struct PointsRecord {
  const FieldStore& points;
  const FieldStore& pending;
  std::vector<double> activation;
  std::vector<double> stage;  // of each pending point (integers held as doubles when gathered)
  const std::vector<double>& stage_start;
  std::vector<double> removed;
  std::int64_t distortion_remaps;
  std::int64_t frozen_discarded;

  void put(StateArchive& a) const {
    a.put_fields("points.", points);
    a.put_fields("pending.", pending);
    a.put("pending.activation_time", activation);
    a.put("pending.stage", std::vector<std::int64_t>(stage.begin(), stage.end()));
    a.put("points.stage_start", stage_start);
    a.put("points.removed", removed);
    a.put_int("points.distortion_remaps", distortion_remaps);
    a.put_int("points.frozen_increments_discarded", frozen_discarded);
  }
};

}  // namespace

void PointSet::save_state(StateArchive& a) const {
  const std::vector<double> removed = removal_record();
  const std::vector<double> stage(pending_stage_.begin(), pending_stage_.end());
  if (!comm_.distributed()) {
    PointsRecord{points_,      pending_, pending_activation_, stage,
                 stage_start_, removed,  distortion_remaps_,  frozen_discarded_}
        .put(a);
    return;
  }
  // Several ranks: rank 0's archive is a serial checkpoint of every rank's points (rank order),
  // plus what a restart on as many ranks needs to give each rank its own back.
  const FieldStore all = gather_points(comm_, points_, 0, false);
  const FieldStore all_pending = gather_points(comm_, pending_, 0, false);
  std::vector<double> activation = gather_values(comm_, pending_activation_);
  std::vector<double> all_stage = gather_values(comm_, stage);
  const std::vector<double> counts = gather_values(
      comm_, {static_cast<double>(points_.size()), static_cast<double>(pending_.size())});
  const std::vector<double> removed_by_rank = gather_values(comm_, removed);
  std::vector<double> totals = removed;
  comm_.sum(totals.data(), static_cast<int>(totals.size()));
  const std::int64_t remaps = distortion_remaps();
  const std::int64_t frozen = frozen_increments_discarded();
  if (comm_.rank() != 0) return;
  PointsRecord{all,          all_pending,       std::move(activation), std::move(all_stage),
               stage_start_, std::move(totals), remaps,                frozen}
      .put(a);
  a.put("points.rank_counts", std::vector<std::int64_t>(counts.begin(), counts.end()));  // active, pending per rank
  a.put("points.removed_by_rank", removed_by_rank);
}

bool PointSet::load_state(const StateArchive& a) {
  a.get_fields("points.", points_);
  a.get_fields("pending.", pending_);
  const std::size_t np = static_cast<std::size_t>(pending_.size());
  pending_activation_ = a.reals("pending.activation_time", np);
  const auto& st = a.ints("pending.stage", np);
  pending_stage_.assign(st.begin(), st.end());
  stage_start_ = a.reals("points.stage_start", stage_start_.size());
  const bool own = written_on_as_many_ranks(a);
  if (comm_.distributed()) {
    const int P = comm_.size(), me = comm_.rank();
    if (own) {
      // Written on as many ranks: this rank's segment of the active and of the pending points.
      const auto& counts = a.ints("points.rank_counts", static_cast<std::size_t>(2 * P));
      Index first = 0, first_pending = 0;
      for (int q = 0; q < me; ++q) {
        first += counts[2 * q];
        first_pending += counts[2 * q + 1];
      }
      keep_ranges(first, first + counts[2 * me], first_pending, first_pending + counts[2 * me + 1]);
    } else {
      keep_share(comm_);
    }
  }
  restore_removed(a, own);
  return own;
}

bool PointSet::written_on_as_many_ranks(const StateArchive& a) const {
  return comm_.distributed() && a.has("points.rank_counts") &&
         a.ints("points.rank_counts").size() == static_cast<std::size_t>(2 * comm_.size());
}

void PointSet::restore_removed(const StateArchive& a, bool own) {
  // A checkpoint written before the per-body record holds only the totals (its bodies lost none
  // that are counted here).
  const std::size_t full = removal_record().size();
  const std::size_t n = a.reals("points.removed").size() == kRemovalTotals ? kRemovalTotals : full;
  std::vector<double> r = a.reals("points.removed", n);
  if (own) {  // this rank's own bookkeeping
    const auto& by_rank = a.reals("points.removed_by_rank", n * static_cast<std::size_t>(comm_.size()));
    r.assign(by_rank.begin() + n * comm_.rank(), by_rank.begin() + n * (comm_.rank() + 1));
  } else if (comm_.rank() != 0) {
    r.assign(n, 0.0);  // the totals once, on rank 0
  }
  r.resize(full, 0.0);
  const std::size_t nb = removed_points_body_.size();
  for (std::size_t b = 0; b < nb; ++b) {
    removed_points_body_[b] = r[kRemovalTotals + b];
    removed_mass_body_[b] = r[kRemovalTotals + nb + b];
    removed_energy_body_[b] = r[kRemovalTotals + 2 * nb + b];
  }
  removed_mass_ = r[0];
  removed_energy_ = r[1];
  removed_chemical_ = r[2];
  removed_momentum_ = Vec3{{r[3], r[4], r[5]}};
  inserted_energy_ = r[6];
  // Only the total matters: rank 0 takes it (a checkpoint without the key has none).
  distortion_remaps_ =
      comm_.rank() == 0 && a.has("points.distortion_remaps") ? a.integer("points.distortion_remaps") : 0;
  frozen_discarded_ = comm_.rank() == 0 && a.has("points.frozen_increments_discarded")
                          ? a.integer("points.frozen_increments_discarded")
                          : 0;
  groups_dirty_ = true;
}

bool PointSet::load_state(const StateArchive& a, const std::vector<std::int64_t>& ids) {
  a.get_fields("points.", points_);
  a.get_fields("pending.", pending_);
  if (pending_.size() > 0) throw Error("PointSet::load_state: pending points are not supported with an id list");
  stage_start_ = a.reals("points.stage_start", stage_start_.size());
  // Every rank read every point: keep this rank's, then put them in id order (the checkpoint holds
  // them in the writing ranks' order).
  const auto* id = points_.ints(kId);
  std::vector<char> keep_mask(static_cast<std::size_t>(points_.size()), 0);
  for (Index p = 0; p < points_.size(); ++p) keep_mask[p] = std::binary_search(ids.begin(), ids.end(), id[p]);
  points_.compact(keep_mask);
  std::vector<Index> order(static_cast<std::size_t>(points_.size()));
  std::iota(order.begin(), order.end(), Index{0});
  id = points_.ints(kId);
  std::sort(order.begin(), order.end(), [&](Index p, Index q) { return id[p] < id[q]; });
  points_.permute(order);
  if (points_.size() != static_cast<Index>(ids.size()))
    throw Error("the checkpoint lacks " + std::to_string(static_cast<Index>(ids.size()) - points_.size()) +
                " of this rank's points");
  pending_activation_.clear();
  pending_stage_.clear();
  const bool same = written_on_as_many_ranks(a);
  restore_removed(a, same);
  return same;
}

}  // namespace ballista
