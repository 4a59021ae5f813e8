#pragma once
// The node coordinates of a graded (rectilinear) grid: resolution where the deck asks for it
// (grid.refine) and coarse cells elsewhere. A shaped-charge jet of 1 mm radius needs about four
// cells across its radius (a rod reaches the hydrodynamic rate within 1 % from four), but only
// near the axis and along its path; a uniform grid at that size pays for it over the whole
// target. Each axis is graded on its own (a tensor-product grid, as the structured mesh
// refinement of GIMP by Ma, Lu & Komanduri, CMES 12 (2006) 213, without hanging nodes): cells of
// each zone's size inside the zone, growing geometrically by at most grid.grading per cell to
// grid.cell_size between zones. A gradual change of cell size keeps the spurious reflection of
// waves crossing it small (tests/verification/test_graded_grid.cpp measures it).
#include <array>
#include <vector>

#include "scenario/scenario.hpp"

namespace ballista {

/// A patch of finer cells (GridPatch) as the grid holds it: its box, with each face that lies on
/// the grid box's face open (the patch goes on into the ghost layers beyond it).
struct PatchBox {
  Vec3 lower, upper;
  std::array<bool, 3> open_lower{}, open_upper{};
  /// 1 for a patch in the grid's own cells, one more for each patch it lies inside.
  int depth = 1;
  /// The patch it lies directly inside (index in GridAxes::patches), -1: none.
  int parent = -1;
  /// Its own nodes per axis over its range: its parent's cells (the grid's without a parent)
  /// split into equal parts.
  std::array<std::vector<double>, 3> lattice;
  /// The most parts a parent cell is split into along an axis.
  int ratio = 1;
  /// x strictly inside (an open face's side unbounded) along the first `dim` axes.
  bool strictly_contains(const Vec3& x, int dim) const;
  /// x in [lower, upper) along the first `dim` axes (an open face's side unbounded): the patch
  /// whose cells a point there starts in.
  bool holds(const Vec3& x, int dim) const;
};

/// Node coordinates of the grid box along each axis (box lower to box upper, increasing; axes
/// beyond the dimension hold the single node 0).
struct GridAxes {
  /// The grid's nodes: the bands' (grid.refine), each cell in a patch's range split.
  std::array<std::vector<double>, 3> node;
  /// The nodes without the patches' splits (equal to `node` without patches).
  std::array<std::vector<double>, 3> base;
  std::vector<PatchBox> patches;
  /// level[k]: the nodes with the splits of the patches of depth <= k (level[0] is `base`, the
  /// last is `node`).
  std::vector<std::array<std::vector<double>, 3>> level;
  /// The deepest patch holding x (PatchBox::holds), -1: none.
  int innermost_holding(const Vec3& x, int dim) const;
  /// The deepest patch strictly containing x, -1: none.
  int innermost_containing(const Vec3& x, int dim) const;
  /// The nodes of patch `patch`'s own cells along the axis (`base` for -1).
  const std::vector<double>& lattice_of(int patch, int axis) const;
  /// Cells of the axis.
  int cells(int axis) const { return static_cast<int>(node[axis].size()) - 1; }
  /// The smallest and largest cell along the axis, m.
  double smallest(int axis) const;
  double largest(int axis) const;
  /// The size of the cell holding coordinate x along the axis, m (beyond the box, the end cell's).
  double cell_size_at(int axis, double x) const;
  /// The size along `axis` of the cell a point at x lies in as the grid's basis sees it: a
  /// patch's own cell inside a patch (the deepest holding x), else the cell without the splits
  /// (the hanging nodes of a split line outside a patch follow the coarse cell's). Points are seeded per this cell and
  /// their stable step is its shortest edge.
  double effective_cell_size(int axis, const Vec3& x, int dim) const;
};

/// Builds the axes of `grid` in `dim` dimensions. A uniform grid (no refine zones) has
/// ceil(extent / cell_size) cells of exactly cell_size per axis, the box's upper face moved out to
/// the last node (as the MPM grid lays it out). On an axis with zones every zone is a whole
/// number of equal cells no larger than its cell_size, from `from` to `to` exactly, and the gaps
/// between zones and the box faces are graded. Throws a DeckError at the offending zone for a
/// zone outside the box, zones that overlap, a zone no finer than grid.cell_size, or a gap too
/// short to grade between its neighbours within grid.grading.
GridAxes build_grid_axes(const GridSpec& grid, int dim);

/// The axes of `grid` without its patches (the bands' only).
GridAxes build_base_axes(const GridSpec& grid, int dim);

}  // namespace ballista
