// Where the MPM solver's points are: sorted by cell, the blocks of nodes their stencils reach, and
// the slabs that make the scatter lock-free.
#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "mpm/mpm_solver.hpp"

namespace ballista {

void MpmSolver::sort_by_cell() {
  // Counting sort of points by cell, slab axis slowest, so that each slab's points are
  // contiguous and neighbouring points share grid nodes in cache.
  const Index n = points_.size();
  if (n == 0) return;
  const GridGeometry& g = grid_.geom;
  const auto* x = points_.view(kPosition);
  std::vector<Index>& key = sort_key_;  // member scratch buffers: no allocation per sort
  key.resize(n);
  const Index ncell = g.node_count();
  for_each(0, n, [&](Index p) {
    int c[3] = {0, 0, 0};
    for (int a = 0; a < dim_; ++a) c[a] = std::clamp(g.cell_of(x[p][a], a), 0, g.nodes[a] - 1);
    key[p] = g.node_index(c[0], c[1], c[2]);
  });
  std::vector<Index>& start = sort_start_;
  start.assign(ncell + 1, 0);
  for (Index p = 0; p < n; ++p) ++start[key[p] + 1];
  for (Index c = 0; c < ncell; ++c) start[c + 1] += start[c];
  std::vector<Index>& order = sort_order_;
  order.resize(n);
  for (Index p = 0; p < n; ++p) order[start[key[p]]++] = p;
  points_.permute(order);
  pts_.mark_reordered();
  if (!point_step_.empty()) {
    // Multi-rate: the own steps follow their points (points activated since: unknown, 0).
    point_step_.resize(static_cast<std::size_t>(n), 0.0);
    std::vector<double> moved(point_step_.size());
    for (Index p = 0; p < n; ++p) moved[p] = point_step_[order[p]];
    point_step_.swap(moved);
  }
}

int MpmSolver::stencil_reach_now() const {
  // Patches: a point's weights on a coarser level's cells reach a coarse cell beyond its own, up
  // to twice as many of the grid's nodes as a hanging node lies from its masters.
  if (!level_geom_.empty()) return std::max(stencil_reach(shape_), 2 * patch_.reach());
  if (shape_ != ShapeKind::Cpdi) return stencil_reach(shape_);
  // CPDI: the corners x_p +- r1 +- r2 +- r3 reach as far as the summed |r_j| components.
  const auto* F = points_.view(kDeformationGradient);
  const auto* half = points_.view(kHalfSize);
  const Index n = points_.size();
  double ext = 0.0;
#pragma omp parallel for reduction(max : ext) schedule(static) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p)
    for (int i = 0; i < dim_; ++i) {
      double e = 0.0;
      for (int j = 0; j < dim_; ++j) e += std::abs(F[p](i, j)) * half[p][j];
      ext = std::max(ext, e);
    }
  return stencil_reach(shape_, ext / grid_.geom.h);
}

void MpmSolver::mark_active_blocks() {
  // On several ranks the F-bar sums each point's cell after the position update (at most a cell
  // from where it starts the step, CFL < 1) across the ranks sharing it: one more cell of reach
  // keeps that cell's corner node in the blocks the ranks exchange.
  const bool fbar_halo = comm_.distributed() && anti_locking_ == AntiLocking::FBar;
  // A hanging node's masters lie up to patch_.reach() nodes from it (patch_constraints.hpp).
  blocks_.mark(x_, points_.size(), reach_ + (fbar_halo ? 1 : 0) + patch_.reach());
  const auto& surface = loads_.surface_forces();
  if (!surface.empty()) {
    std::vector<Vec3> at(surface.size());
    for (std::size_t k = 0; k < surface.size(); ++k) at[k] = surface[k].point;
    blocks_.mark(at.data(), static_cast<Index>(at.size()), reach_);
  }
  if (comm_.distributed())
    for (const MirrorFace& mf : mirror_faces_) blocks_.mark_mirror_images(mf.axis, mf.node, ghost_);
  blocks_.finish();
  if (comm_.distributed()) {
    // Every particle is inside its rank's region after the migration at the start of the step,
    // so a block two ranks share lies within both regions grown by the stencil's reach and a
    // block: only ranks whose grown regions meet exchange their lists. Not so before the first
    // partition, or when bodies were activated this step (they join their rank's region at the
    // next migration): then every rank's list goes to every rank.
    const double reach = static_cast<double>(comm_.max(static_cast<std::int64_t>(reach_)));
    const double margin = (reach + 2.0 + ActiveBlocks::kBlock) * grid_.geom.h;
    if (partition_.ready() && !activated_this_step_) {
      const std::vector<int> nb = partition_.neighbours(margin);
      exchange_.plan(comm_, blocks_, grid_.geom.node_count(), &nb);
      neighbour_sum_ += static_cast<double>(nb.size());
      ++neighbour_plans_;
    } else {
      exchange_.plan(comm_, blocks_, grid_.geom.node_count());
    }
  }
  // Blocks no particle reaches any more go back to zero, as a dense pass would leave them.
  const Index nn = grid_.geom.node_count();
  const bool multi = grid_.fields > 1;
  for (int k = 0; k < grid_.fields; ++k)
    blocks_.for_each_released_node(k * nn, [&](Index i) {
      grid_.mass[i] = 0.0;
      grid_.velocity[i] = grid_.force[i] = grid_.velocity_new[i] = grid_.accel[i] = Vec3{};
      if (multi) grid_.grad[i] = Vec3{};
      if (grid_.with_volume) grid_.volume[i] = 0.0;
    });
}

void MpmSolver::build_slabs(Index begin, Index end) {
  // Lock-free scatter: points are bucketed into slabs of slab_width_ cells along the slab axis.
  // Slabs two apart touch disjoint nodes when width >= 2 * reach, so even slabs are scattered in
  // parallel, then odd ones. Each node thus receives its contributions in an order fixed by the
  // point order alone, so the result does not depend on the thread count.
  const int reach = stencil_reach_now();
  reach_ = reach;
  // Every rank takes this branch together (a rank that threw alone would leave the others waiting
  // in the grid exchange).
  if (comm_.any(reach + 1 > ghost_ && shape_ == ShapeKind::Cpdi)) {
    // A CPDI domain larger than the ghost layers could reach outside the block.
    if (points_.size() == 0 || reach + 1 <= ghost_)
      throw PhysicsError("CPDI particle domain spans more than " + std::to_string(ghost_) + " cells on another rank");
    const auto* F = points_.view(kDeformationGradient);
    Index worst = 0;
    double worst_norm = 0.0;
    for (Index p = 0; p < points_.size(); ++p)
      if (frobenius(F[p]) > worst_norm) { worst_norm = frobenius(F[p]); worst = p; }
    fail(worst, "CPDI particle domain spans more than " + std::to_string(ghost_) + " cells");
  }
  slab_width_ = std::max(2 * reach, 1);
  const GridGeometry& g = grid_.geom;
  const int nslab = (g.nodes[slab_axis_] + slab_width_ - 1) / slab_width_;
  // The points [begin, end) only (multi-rate stepping maps its two classes apart).
  const Index n = points_.size();
  if (end < 0) end = n;
  const auto* x = points_.view(kPosition);
  std::vector<int>& slab = slab_of_point_;  // member scratch: no allocation per step
  slab.resize(n);
  for_each(begin, end, [&](Index p) {
    const int c = std::clamp(g.cell_of(x[p][slab_axis_], slab_axis_), 0, g.nodes[slab_axis_] - 1);
    slab[p] = c / slab_width_;
  });
  slab_start_.assign(nslab + 1, 0);
  for (Index p = begin; p < end; ++p) ++slab_start_[slab[p] + 1];
  for (int s = 0; s < nslab; ++s) slab_start_[s + 1] += slab_start_[s];
  slab_points_.resize(end - begin);
  slab_fill_.assign(slab_start_.begin(), slab_start_.end() - 1);
  for (Index p = begin; p < end; ++p) slab_points_[slab_fill_[slab[p]]++] = p;
}

}  // namespace ballista
