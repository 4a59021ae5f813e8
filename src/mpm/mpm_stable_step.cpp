// MPM's stable time step: the Courant condition per point over its own cell (graded grids) or the
// grid's, with the bulk viscosity's signal speed, and the diagnostic naming the point that sets it.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "mpm/bulk_viscosity.hpp"
#include "mpm/mpm_solver.hpp"

namespace ballista {

namespace {

/// The shortest edge of the cell holding x: the length a signal crosses in the Courant condition.
double shortest_cell_edge(const GridGeometry& g, const Vec3& x, int dim) {
  double l = g.cell_size(g.cell_of(x[0], 0), 0);
  for (int a = 1; a < dim; ++a) l = std::min(l, g.cell_size(g.cell_of(x[a], a), a));
  return l;
}

}  // namespace

void MpmSolver::fill_wave_speeds() {
  wave_scratch_.resize(static_cast<std::size_t>(points_.size()));
  const auto& groups = pts_.material_groups();
  for (std::size_t m = 0; m < groups.size(); ++m)
    if (!groups[m].empty())
      pts_.materials()[m]->wave_speeds(points_, groups[m].data(), static_cast<Index>(groups[m].size()),
                                       wave_scratch_.data());
  pts_.zero_wave_speeds_of_stress_free(wave_scratch_.data());
}

double MpmSolver::stable_dt() {
  drop_patches_if_due();
  const double dt = grid_.geom.graded ? graded_stable_dt() : uniform_stable_dt();
  return multirate_max_ > 1 ? multirate_stable_dt(dt) : dt;
}

double MpmSolver::uniform_stable_dt() {
  // dt = CFL h / max_p (c_p + |v_p|)  (Courant condition with the dilatational wave speed; a
  // point failed to zero stress has no stiffness, c_p = 0: PointSet::zero_wave_speeds_of_stress_free).
  // With the bulk viscosity, its signal speed (Q + sqrt(Q^2 + c^2) + |v|) of the last step's rates.
  fill_wave_speeds();
  const auto* v = points_.view(kVelocity);
  double fastest = 0.0;
  const Index n = points_.size();
#pragma omp parallel for reduction(max : fastest) schedule(static) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p) fastest = std::max(fastest, wave_scratch_[p] + norm(v[p]));
  const double local_max = std::max(fastest, viscous_speed_);
  const double speed = comm_.max(local_max);
  double dt = speed > 0.0 ? scenario_.simulation.cfl * grid_.geom.h / speed
                          : scenario_.simulation.end_time;
  if (scenario_.simulation.max_dt > 0.0) dt = std::min(dt, scenario_.simulation.max_dt);
  return dt;
}

double MpmSolver::cell_edge(const Vec3& x) const {
  if (!patch_axes_) return shortest_cell_edge(grid_.geom, x, dim_);
  const GridGeometry& g = grid_.geom;
  Index c = 0;
  for (int a = dim_ - 1; a >= 0; --a)
    c = c * (g.nodes[a] - 1) + std::clamp(g.cell_of(x[a], a), 0, g.nodes[a] - 2);
  return patch_cell_edge_[static_cast<std::size_t>(c)];
}

void MpmSolver::update_cell_lengths(Index begin, Index end) {
  // The shortest edge of each point's cell: the length a signal crosses in the Courant condition
  // and the viscous length of the bulk viscosity on a graded grid.
  const auto* x = points_.view(kPosition);
  cell_length_.resize(static_cast<std::size_t>(points_.size()));
  for_each(begin, end < 0 ? points_.size() : end, [&](Index p) { cell_length_[p] = cell_edge(x[p]); });
}

double MpmSolver::graded_stable_dt() {
  // dt = CFL min_p l_p / (c_p + |v_p|): each point's signal crosses its own cell (l_p its shortest
  // edge) within the step; with the bulk viscosity, the last pass's signal rates.
  update_cell_lengths();
  const auto* v = points_.view(kVelocity);
  fill_wave_speeds();
  double rate = viscous_rate_;
  const Index n = points_.size();
#pragma omp parallel for reduction(max : rate) schedule(static) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p) rate = std::max(rate, (wave_scratch_[p] + norm(v[p])) / cell_length_[p]);
  if (patch_axes_ && flip_ < 1.0) set_step_cell({});
  double dt = rate > 0.0 ? scenario_.simulation.cfl / rate : scenario_.simulation.end_time;
  if (scenario_.simulation.max_dt > 0.0) dt = std::min(dt, scenario_.simulation.max_dt);
  return dt;
}

void MpmSolver::set_step_cell(const std::vector<char>& skip) {
  // The cell of the point that sets the step (grid_to_particles scales the PIC share by it).
  const auto* v = points_.view(kVelocity);
  double best = -1.0;
  step_cell_ = 0.0;
  for (Index p = 0; p < points_.size(); ++p) {
    if (!skip.empty() && skip[static_cast<std::size_t>(p)]) continue;
    const double r = (wave_scratch_[p] + norm(v[p])) / cell_length_[p];
    if (r > best) {
      best = r;
      step_cell_ = cell_length_[p];
    }
  }
}

StepLimiter MpmSolver::step_limiter() const {
  // Diagnostics only (the run loop calls it when the stable step reaches a new low): the point
  // whose signal crosses its cell fastest, (s_p + |v_p|) / l_p, as stable_dt and the last
  // bulk-viscosity pass bound the step. s_p is the point's wave speed (0 if failed to zero stress),
  // or where the viscosity acts (q > 0) its Q + sqrt(Q^2 + c^2) from the point's L; l_p its cell's
  // shortest edge (graded grids) or h. Collective on several ranks.
  const Index n = points_.size();
  std::vector<double> c(static_cast<std::size_t>(n), 0.0), c_ref;
  std::vector<std::vector<Index>> groups(pts_.materials().size());  // the points of each material
  const auto* mat = points_.ints(kMaterialIndex);
  for (Index p = 0; p < n; ++p) groups[static_cast<std::size_t>(mat[p])].push_back(p);
  const bool viscous = bulk_viscosity_.active();
  if (viscous && bulk_viscosity_.reference_sound_speed) c_ref.assign(c.size(), 0.0);
  for (std::size_t m = 0; m < groups.size(); ++m) {
    if (groups[m].empty()) continue;
    const Index count = static_cast<Index>(groups[m].size());
    pts_.materials()[m]->wave_speeds(points_, groups[m].data(), count, c.data());
    if (!c_ref.empty()) pts_.materials()[m]->reference_wave_speeds(points_, groups[m].data(), count, c_ref.data());
  }
  pts_.zero_wave_speeds_of_stress_free(c.data());
  const GridGeometry& g = grid_.geom;
  const auto* x = points_.view(kPosition);
  const auto* v = points_.view(kVelocity);
  const auto* F = points_.view(kDeformationGradient);
  const auto* L = points_.view(kVelocityGradient);
  const double* q = viscous ? points_.real(kBulkViscosity) : nullptr;
  const auto* id = points_.ints(kId);
  const auto* body = points_.ints(kBodyIndex);
  StepLimiter out;
  double best = -1.0;
  // Every point's rate, for the multi-rate figure and the margin (one rank only: see below).
  std::vector<double> rates(comm_.distributed() ? 0 : static_cast<std::size_t>(n));
  for (Index p = 0; p < n; ++p) {
    const double l = g.graded ? cell_edge(x[p]) : g.h;
    const double s = q ? point_signal_speed(bulk_viscosity_, q[p], c[p], l, L[p], c_ref.empty() ? c[p] : c_ref[p]) : c[p];
    const bool by_q = s > c[p];
    const double speed = norm(v[p]);
    const double rate = (s + speed) / l;
    if (!rates.empty()) rates[static_cast<std::size_t>(p)] = rate;
    if (rate > best) {
      best = rate;
      out = {id[p], static_cast<int>(body[p]), s, speed, det(F[p]), g.graded ? l : 0.0, by_q};
    }
  }
  if (!comm_.distributed()) {
    // Each point in the class of its own step, best / rate rounded down to a power of two: 2^-k of
    // the updates (a point without a signal, at rest and stress-free, in the coarsest class).
    if (best > 0.0) {
      double updates = 0.0;
      for (const double r : rates)
        updates += std::ldexp(1.0, -(r > 0.0 ? std::min(kMultirateLevels, std::ilogb(best / r)) : kMultirateLevels));
      out.multirate = static_cast<double>(n) / updates;
    }
    // The rate of the fastest point beyond the fastest thousandth (n / 1000 points, at least one):
    // the step those few hold the run to, against the one the rest would allow.
    const std::size_t k = static_cast<std::size_t>(std::max<Index>(1, n / 1000));
    if (best > 0.0 && rates.size() > k) {
      std::nth_element(rates.begin(), rates.begin() + static_cast<std::ptrdiff_t>(k), rates.end(),
                       std::greater<double>());
      if (rates[k] > 0.0) out.margin = best / rates[k];
    }
    return out;
  }
  comm_.broadcast(&out, sizeof out, comm_.rank_of_max(best));
  return out;
}

}  // namespace ballista
