// Multi-rate stepping for MPM (mpm.multirate): points whose own stable step is several
// times the fastest point's take one step while the fast ones take several substeps.
//
// The scheme is element-partitioned subcycling (Belytschko, Yen & Mullen, "Mixed methods for time
// integration", CMAME 17/18 (1979) 259; Belytschko, Smolinski & Liu, CMAME 49 (1985) 281), with
// MPM's points as the elements: the slow points map their mass, momentum and forces (from the
// stress at the step's start, USAVG's first half) once per step; their share of each node is held
// over the substeps, the fast points map theirs at every substep, and the grid update acts on the
// sum. The velocity the slow share sees, u, changes at each substep by the node's whole change
// (force, contact and constraints), so momentum is conserved node by node; where only slow points
// reach a node the substeps with a constant force add up to one step of the slow points' length
// exactly. At the step's end the slow points take their FLIP change from u, and their path and
// strain from the node's velocity over the substeps, on which their held forces did their work
// (slow_grid_to_particles). A slow point's own stable step covers the whole step (each point's
// Courant condition over its own cell, as stable_dt), and the points within kMultirateBuffer
// cells of a fast one step fast too, so that no fast point reaches a slow one's cells within a
// step at the 8 substeps a step may hold.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "mpm/bulk_viscosity.hpp"
#include "mpm/mpm_solver.hpp"

namespace ballista {

namespace {
/// Cells around a fast point's cell whose points step fast too.
constexpr int kMultirateBuffer = 2;
}  // namespace

double MpmSolver::multirate_stable_dt(double single_dt) {
  // Each point's own stable step, CFL l_p / (s_p + |v_p|) as stable_dt takes it (s_p the wave
  // speed, or the bulk viscosity's signal speed from the point's last L where q acts).
  const Index n = points_.size();
  const auto* v = points_.view(kVelocity);
  const auto* L = points_.view(kVelocityGradient);
  const double* q = bulk_viscosity_.active() ? points_.real(kBulkViscosity) : nullptr;
  std::vector<double> c_ref;
  if (q && bulk_viscosity_.reference_sound_speed) {
    c_ref.assign(static_cast<std::size_t>(n), 0.0);
    const auto& groups = pts_.material_groups();
    for (std::size_t m = 0; m < groups.size(); ++m)
      if (!groups[m].empty())
        pts_.materials()[m]->reference_wave_speeds(points_, groups[m].data(), static_cast<Index>(groups[m].size()),
                                                   c_ref.data());
  }
  const double cfl = scenario_.simulation.cfl;
  point_step_.resize(static_cast<std::size_t>(n));
  double fastest = 0.0;
  // Points at rest out of every moving point's reach this step take any step unchanged
  // (multirate_idle.cpp): slow, and not the fastest.
  const std::vector<char> idle = idle_points();
  idle_ids_.clear();
  if (!idle.empty()) {
    const auto* id = points_.ints(kId);
    for (Index p = 0; p < n; ++p)
      if (idle[static_cast<std::size_t>(p)]) idle_ids_.push_back(id[p]);
    std::sort(idle_ids_.begin(), idle_ids_.end());
  }
  // wave_scratch_ holds the wave speeds stable_dt has just filled.
  for (Index p = 0; p < n; ++p) {
    if (!idle.empty() && idle[static_cast<std::size_t>(p)]) {
      point_step_[p] = std::numeric_limits<double>::infinity();
      continue;
    }
    const double l = grid_.geom.graded ? cell_length_[p] : grid_.geom.h;
    const double c = wave_scratch_[p];
    const double s = q ? point_signal_speed(bulk_viscosity_, q[p], c, l, L[p], c_ref.empty() ? c : c_ref[p]) : c;
    const double rate = (s + norm(v[p])) / l;
    fastest = std::max(fastest, rate);
    point_step_[p] = rate > 0.0 ? cfl / rate : std::numeric_limits<double>::infinity();
  }
  double fine = fastest > 0.0 ? cfl / fastest : single_dt;
  if (idle.empty()) {
    fine = std::min(fine, single_dt);
  } else {
    // single_dt holds the idle points to their Courant step too: the cap is the limit alone, and
    // the PIC share's reference cell the fastest moving point's.
    if (scenario_.simulation.max_dt > 0.0) fine = std::min(fine, scenario_.simulation.max_dt);
    if (patch_axes_ && flip_ < 1.0) set_step_cell(idle);
  }
  fine_dt_ = fine;
  // The ratio with the fewest point updates per unit time: R = 2^j makes the points whose step
  // is below R fine_dt step R times, the rest once.
  int classes[8] = {};
  for (Index p = 0; p < n; ++p) {
    const double r = point_step_[p] / fine;
    const int k = r >= 128.0 ? 7 : std::max(0, std::ilogb(r));
    ++classes[k];
  }
  int best_ratio = 1;
  double best_cost = static_cast<double>(n);
  for (int ratio = 2; ratio <= multirate_max_; ratio *= 2) {
    double fast = 0.0;
    for (int k = 0; k < 8 && (1 << k) < ratio; ++k) fast += classes[k];
    const double cost = (ratio * fast + (static_cast<double>(n) - fast)) / ratio;
    if (cost < 0.95 * best_cost) {  // a ratio that saves less than 5 % is not worth its grid passes
      best_cost = cost;
      best_ratio = ratio;
    }
  }
  double dt = best_ratio * fine;
  if (scenario_.simulation.max_dt > 0.0) dt = std::min(dt, scenario_.simulation.max_dt);
  return dt;
}

double MpmSolver::land_step(double dt) const {
  // Points waiting for activation (a jet's segments at their arrival) enter at the start of the
  // step that begins at or after their time: with multi-rate steps the step lands on it, a hair
  // past so that the sum of the steps is not an ulp short. The slow points' step, idle points left
  // out, can be many times the step they would wait in otherwise, and a segment entering that late
  // would arrive late. One step for all is left as it was.
  if (multirate_max_ <= 1) return dt;
  const double gap = pts_.next_activation(time_) - time_;
  return gap < dt ? std::min(dt, gap * (1.0 + 1e-12) + 1e-12 * dt) : dt;
}

Index MpmSolver::partition_by_rate(double dt) {
  // Fast: a point whose own step is shorter than dt (or unknown: activated since stable_dt), and
  // every point in the cells within kMultirateBuffer of a fast point's cell.
  const Index n = points_.size();
  const GridGeometry& g = grid_.geom;
  const auto* x = points_.view(kPosition);
  std::vector<char> fast(static_cast<std::size_t>(n), 0);
  const Index known = static_cast<Index>(point_step_.size());
  for (Index p = 0; p < n; ++p) fast[p] = p >= known || point_step_[p] < dt * (1.0 - 1e-12);
  int cells[3] = {1, 1, 1};
  for (int a = 0; a < dim_; ++a) cells[a] = g.nodes[a] - 1;
  auto flat = [&](const int* c) { return (static_cast<std::size_t>(c[2]) * cells[1] + c[1]) * cells[0] + c[0]; };
  std::vector<std::array<int, 3>> cell(static_cast<std::size_t>(n));
  for_each(0, n, [&](Index p) {
    for (int a = 0; a < 3; ++a) cell[p][a] = a < dim_ ? std::clamp(g.cell_of(x[p][a], a), 0, cells[a] - 1) : 0;
  });
  std::vector<char> near(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2], 0);
  const int b = kMultirateBuffer;
  for (Index p = 0; p < n; ++p) {
    if (!fast[p]) continue;
    const int* c = cell[p].data();
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = a < dim_ ? std::max(0, c[a] - b) : 0;
      hi[a] = a < dim_ ? std::min(cells[a] - 1, c[a] + b) : 0;
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          const int ci[3] = {i, j, k};
          near[flat(ci)] = 1;
        }
  }
  std::vector<Index>& order = sort_order_;
  order.clear();
  order.reserve(static_cast<std::size_t>(n));
  std::vector<Index> slow;
  for (Index p = 0; p < n; ++p) {
    if (fast[p] || near[flat(cell[p].data())])
      order.push_back(p);
    else
      slow.push_back(p);
  }
  const Index nfast = static_cast<Index>(order.size());
  if (!slow.empty()) {
    // Fast points first, each class in its order (the cell sort's, which the scatter's cache
    // locality wants).
    order.insert(order.end(), slow.begin(), slow.end());
    points_.permute(order);
    pts_.mark_reordered();
  }
  return nfast;
}

template <int Dim, ShapeKind K, bool G>
void MpmSolver::step_multirate(double dt, int substeps) {
  const double h = dt / substeps;
  const Index nfast = partition_by_rate(dt);
  Index n = points_.size();
  if (nfast == n) {  // every point fast: plain steps
    for (int k = 0; k < substeps; ++k) {
      step_impl<Dim, K, G>(h);
      --steps_;  // the run counts the step, not its substeps
      if (k + 1 < substeps) handle_exits();
    }
    ++steps_;
    multirate_tally_.steps += 1.0;
    multirate_tally_.substeps += substeps;
    multirate_tally_.fast_point_steps += static_cast<double>(substeps) * static_cast<double>(n);
    multirate_tally_.single_rate_point_steps += static_cast<double>(substeps) * static_cast<double>(n);
    return;
  }
  Index nf = nfast;
  bind_fields();
  if constexpr (K == ShapeKind::Gimp) gimp_windows_of_points<Dim>().resize(points_.size());
  if (!level_geom_.empty()) stencil_level_.resize(static_cast<std::size_t>(points_.size()));
  loads_.compute(scenario_, points_, time_);
  // The slow points' loads of this step (their positions do not change within it).
  MultirateGrid& mg = multirate_;
  {
    const std::vector<Vec3>& fext = loads_.total();
    const std::vector<Vec3>& ftrac = loads_.traction();
    mg.fext.clear();
    if (!fext.empty())
      for (Index p = nf; p < n; ++p) mg.fext.push_back(ftrac.empty() ? fext[p] : fext[p] - ftrac[p]);
    mg.surface.clear();
    for (const PointLoads::SurfaceForce& sf : loads_.surface_forces())
      if (sf.index >= nf) mg.surface.push_back(sf);
  }
  build_slabs(nf, n);
  mark_active_blocks();
  // The slow points' slabs are kept for their forces' mapping below (the slabs of the fast points
  // are built in their place).
  auto swap_slabs = [&] {
    slab_start_.swap(mg.slab_start);
    slab_points_.swap(mg.slab_points);
  };
  const Index nall = grid_.geom.node_count() * grid_.fields;
  const bool multi = grid_.fields > 1;
  // The slow share: mass and momentum (and the contact's sums) ...
  windows_current_ = false;
  particles_to_grid<Dim, K, G>(P2gPart::Kinematics, nullptr, nf, n);
  mg.mass = grid_.mass;
  if (multi) mg.grad = grid_.grad;
  if (grid_.with_volume) mg.volume = grid_.volume;
  mg.u.assign(static_cast<std::size_t>(nall), Vec3{});
  for_each_active_node([&](Index i) {
    const double m = mg.mass[i];
    mg.u[i] = m > kTinyMass ? (1.0 / m) * grid_.velocity[i] : Vec3{};
  });
  if (!patch_.empty()) fill_patch_nodes(mg.u.data());
  if (!mirror_faces_.empty()) fill_mirror_ghosts(mg.u.data());
  mg.u0 = mg.u;
  mg.disp.assign(static_cast<std::size_t>(nall), Vec3{});
  swap_slabs();
  for (int k = 0; k < substeps; ++k) {
    const double t = time_ + k * h;
    if (k > 0) loads_.compute(scenario_, points_, t);
    build_slabs(0, nf);
    if (k > 0) mark_active_blocks();
    // The fast points' sums, then the slow share added. The GIMP windows of the fast points are
    // computed anew (they moved), then kept for the substep's passes; the slow points' stay
    // those of the step's start (they have not moved).
    windows_current_ = false;
    particles_to_grid<Dim, K, G>(P2gPart::Kinematics, nullptr, 0, nf);
    windows_current_ = K == ShapeKind::Gimp;
    for_each_active_node([&](Index i) {
      const double m = mg.mass[i];
      if (!(m > 0.0)) return;
      grid_.mass[i] += m;
      grid_.velocity[i] += m * mg.u[i];
      if (multi) grid_.grad[i] += mg.grad[i];
      if (grid_.with_volume) grid_.volume[i] += mg.volume[i];
    });
    usavg_start_velocity();
    first_half_points<Dim, K, G>(h, 0, nf);
    if (k == 0) {
      // The slow points' first half over the whole step from the same v_n, then their forces.
      first_half_points<Dim, K, G>(dt, nf, n);
      mg.vn0 = usavg_start_;
      swap_slabs();
      particles_to_grid<Dim, K, G>(P2gPart::Forces, nullptr, nf, n);
      swap_slabs();
      mg.force = grid_.force;
      if (grid_.with_volume) mg.volume_forces = grid_.volume;  // the half-updated volumes
    }
    particles_to_grid<Dim, K, G>(P2gPart::Forces, nullptr, 0, nf);
    for_each_active_node([&](Index i) {
      grid_.force[i] += mg.force[i];
      if (grid_.with_volume) grid_.volume[i] += mg.volume_forces[i];  // the forces' pass maps them anew
    });
    update_grid(h);
    grid_to_particles<Dim, K, G, true>(h, 0, nf);
    transfer_work_ -= grid_kinetic_energy_change(h);
    // The slow share's velocity takes the node's whole change (its momentum is conserved with
    // the node's); the node's path is the substep's (v_n + v_end) / 2, as USAVG moves points. The
    // path is the node's, not the share's: the slow points' forces work on the node's velocity in
    // the grid's energy, so their strain must be the node's too for the energy to balance.
    for_each_active_node([&](Index i) {
      mg.u[i] += h * grid_.accel[i];
      mg.disp[i] += (0.5 * h) * (usavg_start_[i] + grid_.velocity_new[i]);
    });
    if (first_bad_ < points_.size())
      pts_.fail(first_bad_, "inverted or non-finite deformation gradient (J <= 0, NaN or infinite)", steps_ + 1, t + h);
    pts_.update_stress(0.5 * h, steps_ + 1, t + h, {}, 0, nf);
    if (bulk_viscosity_.active()) bulk_viscosity_pass(0.5 * h, false, 0, nf);
    if (k + 1 < substeps && first_out_ < points_.size()) {
      // Fast points that left the grid go now (the slow ones have not moved): the slow range
      // keeps its order and moves down.
      handle_exits();
      const Index removed = n - points_.size();
      nf -= removed;
      for (PointLoads::SurfaceForce& sf : mg.surface) sf.index -= removed;
      n = points_.size();
      bind_fields();
    }
  }
  multirate_tally_.steps += 1.0;
  multirate_tally_.substeps += substeps;
  multirate_tally_.fast_point_steps += static_cast<double>(substeps) * static_cast<double>(nf);
  multirate_tally_.slow_point_steps += static_cast<double>(n - nf);
  multirate_tally_.single_rate_point_steps += static_cast<double>(substeps) * static_cast<double>(n);
  // The slow points: w = 2 disp / dt - v_n for their second stress half, then their update.
  for_each_active_node([&](Index i) { mg.vn0[i] = (2.0 / dt) * mg.disp[i] - mg.vn0[i]; });
  windows_current_ = false;  // fast points that left may have shifted the slow ones' indices
  slow_grid_to_particles<Dim, K, G>(dt, substeps, nf, n);
  windows_current_ = false;
  time_ += dt;
  ++steps_;
  if (const std::int64_t d = frozen_discarded_.exchange(0)) pts_.add_frozen_increments_discarded(d);
  if (first_bad_ < points_.size())
    fail(first_bad_, "inverted or non-finite deformation gradient (J <= 0, NaN or infinite)");
  pts_.update_stress(0.5 * dt, steps_, time_, {}, nf, n);
  if (bulk_viscosity_.active()) bulk_viscosity_pass(0.5 * dt, false, nf, n);
}

#define BALLISTA_MULTIRATE(Dim, K, G) template void MpmSolver::step_multirate<Dim, K, G>(double, int);
BALLISTA_MULTIRATE(2, ShapeKind::Linear, false)
BALLISTA_MULTIRATE(3, ShapeKind::Linear, false)
BALLISTA_MULTIRATE(2, ShapeKind::Gimp, false)
BALLISTA_MULTIRATE(3, ShapeKind::Gimp, false)
BALLISTA_MULTIRATE(2, ShapeKind::Cpdi, false)
BALLISTA_MULTIRATE(3, ShapeKind::Cpdi, false)
BALLISTA_MULTIRATE(2, ShapeKind::BSpline3, false)
BALLISTA_MULTIRATE(3, ShapeKind::BSpline3, false)
BALLISTA_MULTIRATE(2, ShapeKind::Linear, true)
BALLISTA_MULTIRATE(3, ShapeKind::Linear, true)
BALLISTA_MULTIRATE(2, ShapeKind::Gimp, true)
BALLISTA_MULTIRATE(3, ShapeKind::Gimp, true)
BALLISTA_MULTIRATE(2, ShapeKind::Cpdi, true)
BALLISTA_MULTIRATE(3, ShapeKind::Cpdi, true)
#undef BALLISTA_MULTIRATE

}  // namespace ballista
