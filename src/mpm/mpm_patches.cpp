// Patches of finer cells (grid.patches) in the MPM solver: the checks and tables set up once
// (refusals, each grid cell's region cell edge, the coarser nesting levels' grids a uGIMP point
// takes its weights on), and the per-step fold and fill of the hanging nodes
// (mpm/patch_constraints.hpp; why: docs/architecture.md, "Patches").
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "geometry/grid_axes.hpp"
#include "mpm/graded_shape_functions.hpp"
#include "mpm/mpm_solver.hpp"

namespace ballista {

void MpmSolver::setup_patches(const Scenario& sc) {
  const DeckMark& m = sc.grid.patches.front().mark;
  auto refuse = [&](const std::string& why) { throw DeckError(m.file, m.line, m.column, "grid.patches", why); };
  if (anti_locking_ == AntiLocking::FBar)
    refuse("the F-bar averages over the grid's cells, which a patch's hanging nodes do not bound: "
           "patches run without mpm.anti_locking: fbar so far");
  if (xpic_active())
    refuse("XPIC smooths over the grid's nodes, hanging ones included: patches run without "
           "mpm.xpic_order > 1 so far");
  patch_axes_ = std::make_shared<const GridAxes>(build_grid_axes(sc.grid, dim_));
  patch_ = PatchConstraints(grid_.geom, *patch_axes_, kGhostLayers);
  {
    // A patch's faces lie on the grid's nodes, so each grid cell lies in one region.
    const GridGeometry& g = grid_.geom;
    const int cells[3] = {g.nodes[0] - 1, g.nodes[1] - 1, dim_ == 3 ? g.nodes[2] - 1 : 1};
    patch_cell_edge_.resize(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2]);
    std::size_t at = 0;
    for (int k = 0; k < cells[2]; ++k)
      for (int j = 0; j < cells[1]; ++j)
        for (int i = 0; i < cells[0]; ++i) {
          const int ijk[3] = {i, j, k};
          Vec3 centre{};
          for (int a = 0; a < dim_; ++a)
            centre[a] = 0.5 * ((*g.graded)[a].at(ijk[a]) + (*g.graded)[a].at(ijk[a] + 1));
          double l = patch_axes_->effective_cell_size(0, centre, dim_);
          for (int a = 1; a < dim_; ++a)
            l = std::min(l, patch_axes_->effective_cell_size(a, centre, dim_));
          patch_cell_edge_[at++] = l;
        }
  }
  if (shape_ == ShapeKind::Gimp)
    for (std::size_t i = 0; i < patch_axes_->patches.size(); ++i)
      if (patch_axes_->patches[i].ratio > 2) {
        const DeckMark& pm = sc.grid.patches[i].mark;
        throw DeckError(
            pm.file, pm.line, pm.column, fmt::format("{}.cell_size", pm.key_path),
            fmt::format(
                "splits its parent's cells into {} along an axis: with uGIMP a patch splits "
                "cells in two at most (a coarse point crossing its face would take a domain "
                "clamped to the split cells and leave a static imbalance); nest patches for "
                "finer cells, each in two",
                patch_axes_->patches[i].ratio));
      }
  if (shape_ == ShapeKind::Linear)
    for (std::size_t i = 0; i < patch_axes_->patches.size(); ++i)
      if (patch_axes_->patches[i].depth > 1) {
        spdlog::warn(
            "{} is a nested patch and the shape functions are linear: points that flow into it from "
            "coarser cells are further apart than its cells, which then go empty, and they can invert "
            "(the B2 vortex with nested patches stops at its 276th step; docs/deck.md); gimp does not",
            sc.grid.patches[i].mark.key_path);
        break;
      }
  // Each coarser level's grid, laid out as layout_graded_grid lays out the grid, and where its
  // nodes are in the grid: the box's nodes are the grid's (a split only adds nodes); a ghost
  // layer matches where the grid's end cell is not split further.
  const int levels = static_cast<int>(patch_axes_->level.size()) - 1;
  for (int lv = 0; lv < levels; ++lv) {
    GridGeometry geom = grid_.geom;
    auto level_axes = std::make_shared<std::array<GradedAxis, 3>>();
    std::array<std::vector<int>, 3> to_grid;
    for (int a = 0; a < 3; ++a) {
      if (a >= dim_) {
        to_grid[a] = {0};
        continue;
      }
      const std::vector<double>& box = patch_axes_->level[static_cast<std::size_t>(lv)][a];
      const double first = box[1] - box[0];
      const std::vector<double> nodes = with_ghost_layers(box, kGhostLayers);
      (*level_axes)[a] = GradedAxis(nodes);
      geom.nodes[a] = static_cast<int>(nodes.size());
      const GradedAxis& grid_axis = (*grid_.geom.graded)[a];
      int from = 0;
      for (const double xn : nodes) {
        int found = -1;
        for (int i = from; i < grid_.geom.nodes[a]; ++i)
          if (std::abs(grid_axis.at(i) - xn) <= 1e-9 * first) {
            found = i;
            from = i + 1;
            break;
          }
        to_grid[a].push_back(found);
      }
    }
    geom.graded = std::move(level_axes);
    std::vector<Index> map(static_cast<std::size_t>(geom.node_count()), -1);
    for (int k = 0; k < geom.nodes[2]; ++k)
      for (int j = 0; j < geom.nodes[1]; ++j)
        for (int i = 0; i < geom.nodes[0]; ++i) {
          const int gi = to_grid[0][static_cast<std::size_t>(i)],
                    gj = to_grid[1][static_cast<std::size_t>(j)],
                    gk = to_grid[2][static_cast<std::size_t>(k)];
          if (gi >= 0 && gj >= 0 && gk >= 0)
            map[static_cast<std::size_t>(geom.node_index(i, j, k))] =
                grid_.geom.node_index(gi, gj, gk);
        }
    level_geom_.push_back(std::move(geom));
    level_to_grid_.push_back(std::move(map));
  }
}

void MpmSolver::drop_patches_if_due() {
  // Patches serve a phase of the run (the casing's hole opening under the jet); after it their
  // fine cells would keep setting their points' short steps. MPM carries its state on the points,
  // so the grid may change between steps (as an AMR MPM code regrids): each point keeps its
  // state, mass, volume and uGIMP domain and maps from now on to the grid without the patches,
  // whose cells then set its step. Only the grid's own arrays and tables are rebuilt; the points
  // are not re-sorted, so that a run restarted from a checkpoint written after the drop (whose
  // solver drops again at its first step) proceeds bitwise as the run that was not stopped.
  if (!patch_axes_ || patches_dropped_) return;
  const double until = scenario_.grid.patches.front().until;
  if (!(time_ >= pts_.main_stage_start() + until)) return;
  Scenario coarse = scenario_;
  coarse.grid.patches.clear();
  rebuild_grid(coarse);
  patches_dropped_ = true;
  spdlog::info("grid.patches dropped at t = {:.6g} s ({:g} s into the main stage, their until): {} grid nodes now",
               time_, until, grid_.geom.node_count());
}

void MpmSolver::restore_patches_if_due() {
  // A state loaded into this solver from before the patches' end (the replay of the steps before
  // a failure starts from the newest checkpoint) runs on the patched grid again.
  if (!patches_dropped_) return;
  if (time_ >= pts_.main_stage_start() + scenario_.grid.patches.front().until) return;
  rebuild_grid(scenario_);
  setup_patches(scenario_);
  patches_dropped_ = false;
}

void MpmSolver::rebuild_grid(const Scenario& sc) {
  layout_ = layout_grid(sc, kGhostLayers);
  const int fields = grid_.fields;
  const bool with_volume = grid_.with_volume;
  grid_ = GridData{};
  grid_.geom = layout_.geom;
  grid_.fields = fields;
  grid_.with_volume = with_volume;
  grid_.resize(grid_.geom.node_count() * grid_.fields);
  blocks_.reset(grid_.geom);
  patch_ = PatchConstraints{};
  patch_axes_.reset();
  patch_cell_edge_.clear();
  level_geom_.clear();
  level_to_grid_.clear();
  stencil_level_.clear();
  windows_current_ = false;
  usavg_start_.clear();
  multirate_ = MultirateGrid{};
  step_cell_ = 0.0;
}

bool MpmSolver::clear_of_patches(const Vec3& x, const Vec3& half, int depth) const {
  if (dimension_ == Dimension::Axisymmetric && !(x[0] - half[0] > 0.0)) return false;
  for (const PatchBox& b : patch_axes_->patches) {
    if (b.depth < depth) continue;
    bool overlap = true;
    for (int a = 0; a < dim_ && overlap; ++a) {
      const bool below =
          !b.open_lower[static_cast<std::size_t>(a)] && !(x[a] + half[a] > b.lower[a]);
      const bool above =
          !b.open_upper[static_cast<std::size_t>(a)] && !(x[a] - half[a] < b.upper[a]);
      overlap = !(below || above);
    }
    if (overlap) return false;
  }
  return true;
}

template <int Dim>
void MpmSolver::patch_point_stencil(Index p, const Vec3& x, const Vec3& half, GimpWindows<Dim>& w,
                                    Stencil<Dim>& st) {
  // A domain clear of the patches deeper than level k takes its weights on level k's cells
  // (level_geom_), the coarsest such level; the rest the grid's own.
  const int grid_level = static_cast<int>(level_geom_.size());
  char& level = stencil_level_[static_cast<std::size_t>(p)];
  if (!windows_current_) {
    level = static_cast<char>(grid_level);
    for (int k = 0; k < grid_level; ++k) {
      if (!clear_of_patches(x, half, k + 1)) continue;
      graded_gimp_windows<Dim>(level_geom_[static_cast<std::size_t>(k)], x, half, w);
      stencil_from_windows<Dim>(level_geom_[static_cast<std::size_t>(k)], w, st);
      bool mapped = true;
      const std::vector<Index>& to_grid = level_to_grid_[static_cast<std::size_t>(k)];
      for (int q = 0; q < st.count && mapped; ++q) mapped = to_grid[static_cast<std::size_t>(st.node[q])] >= 0;
      if (mapped) {
        level = static_cast<char>(k);
        break;
      }
    }
    if (level == grid_level) graded_gimp_windows<Dim>(grid_.geom, x, half, w);
  }
  if (level < grid_level) {
    stencil_from_windows<Dim>(level_geom_[static_cast<std::size_t>(level)], w, st);
    const std::vector<Index>& to_grid = level_to_grid_[static_cast<std::size_t>(level)];
    for (int q = 0; q < st.count; ++q) st.node[q] = to_grid[static_cast<std::size_t>(st.node[q])];
    return;
  }
  stencil_from_windows<Dim>(grid_.geom, w, st);
}

template void MpmSolver::patch_point_stencil<2>(Index, const Vec3&, const Vec3&, GimpWindows<2>&, Stencil<2>&);
template void MpmSolver::patch_point_stencil<3>(Index, const Vec3&, const Vec3&, GimpWindows<3>&, Stencil<3>&);

void MpmSolver::fold_patch_nodes(P2gPart part) {
  const Index nn = grid_.geom.node_count();
  const int nf = grid_.fields;
  if (maps_mass(part)) {
    patch_.fold(grid_.mass.data(), nn, nf);
    if (nf > 1) patch_.fold(grid_.grad.data(), nn, nf);
  }
  if (maps_momentum(part)) patch_.fold(grid_.velocity.data(), nn, nf);
  if (maps_forces(part)) patch_.fold(grid_.force.data(), nn, nf);
  if (maps_volume(part) && grid_.with_volume) patch_.fold(grid_.volume.data(), nn, nf);
}

void MpmSolver::fill_patch_nodes(Vec3* v) const {
  patch_.fill(v, grid_.geom.node_count(), grid_.fields);
}

}  // namespace ballista
