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

/// Node coordinates of the grid box along each axis (box lower to box upper, increasing; axes
/// beyond the dimension hold the single node 0).
struct GridAxes {
  std::array<std::vector<double>, 3> node;
  /// Cells of the axis.
  int cells(int axis) const { return static_cast<int>(node[axis].size()) - 1; }
  /// The smallest and largest cell along the axis, m.
  double smallest(int axis) const;
  double largest(int axis) const;
  /// The size of the cell holding coordinate x along the axis, m (beyond the box, the end cell's).
  double cell_size_at(int axis, double x) const;
};

/// Builds the axes of `grid` in `dim` dimensions. A uniform grid (no refine zones) has
/// ceil(extent / cell_size) cells of exactly cell_size per axis, the box's upper face moved out to
/// the last node (as the MPM grid lays it out). On an axis with zones every zone is a whole
/// number of equal cells no larger than its cell_size, from `from` to `to` exactly, and the gaps
/// between zones and the box faces are graded. Throws a DeckError at the offending zone for a
/// zone outside the box, zones that overlap, a zone no finer than grid.cell_size, or a gap too
/// short to grade between its neighbours within grid.grading.
GridAxes build_grid_axes(const GridSpec& grid, int dim);

}  // namespace ballista
