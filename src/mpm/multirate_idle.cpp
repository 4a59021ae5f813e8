// Points the multi-rate step need not hold to their own stable step: at rest, stress-free and
// unloaded, and out of reach of every other point within the step. A body waiting for a jet, a
// plate ahead of its stress wave, a cylinder's far end are such points; in the shaped-charge demo
// the casing and the cement sit in the finest cells for the 16 us the jet takes to arrive, and
// their Courant step would set the whole run's.
//
// Why leaving them out of the step's choice is exact, not an approximation: in MPM a point changes
// only through the nodes of its stencil. Within one substep of USAVG a change crosses from a point
// to the nodes it maps to, to the points that read those nodes (the first stress half), to their
// nodes (the forces) and to the points that read them (the update): two hops from point to point,
// each no further than two stencils' reach (shape_functions.hpp) and a hanging node's masters
// (which lie in the coarsest level's cell that holds it) plus the path of a point within a
// substep (under one cell at CFL < 1). Empty cells carry nothing. So a point at rest whose cell no moving point can reach
// through occupied cells in 2 R hops sees every node of its stencil at zero velocity and zero force
// for the whole step, whatever the step's length: its update leaves it at rest, stress-free, where
// it was, as one step for all with any dt would. It joins the slow points (its update costs one
// per step) and does not enter the fastest point's step; once a moving point comes within that
// reach it is held to its own Courant step again, a step before anything can arrive.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "core/point_fields.hpp"
#include "mpm/bulk_viscosity.hpp"
#include "mpm/mpm_solver.hpp"

namespace ballista {

namespace {

/// Sets every cell within `radius` cells (along each axis: a box) of a set cell of `mask`.
void dilate(std::vector<char>& mask, const int* cells, int dim, int radius) {
  if (radius <= 0) return;
  for (int a = 0; a < dim; ++a) {
    const std::size_t stride = a == 0 ? 1 : a == 1 ? static_cast<std::size_t>(cells[0])
                                                   : static_cast<std::size_t>(cells[0]) * cells[1];
    const int len = cells[a];
    const std::size_t lines = mask.size() / static_cast<std::size_t>(len);
    std::vector<int> last(static_cast<std::size_t>(len));
    for (std::size_t line = 0; line < lines; ++line) {
      // The line's first cell: lines run over the other axes' cells in order.
      const std::size_t below = line % stride, above = line / stride;
      const std::size_t first = above * stride * static_cast<std::size_t>(len) + below;
      auto at = [&](int i) -> char& { return mask[first + static_cast<std::size_t>(i) * stride]; };
      // The distance to the nearest set cell on either side, in two sweeps.
      int near = -1 - radius;
      for (int i = 0; i < len; ++i) {
        if (at(i)) near = i;
        last[static_cast<std::size_t>(i)] = i - near;
      }
      near = len + radius;
      for (int i = len - 1; i >= 0; --i) {
        if (at(i)) near = i;
        if (std::min(last[static_cast<std::size_t>(i)], near - i) <= radius) at(i) = 1;
      }
    }
  }
}

/// Point p exactly at rest: no velocity, no stress, no viscous pressure (q null: none kept).
bool at_rest(const Vec3* v, const Mat3* sigma, const double* q, Index p) {
  bool rest = !q || q[p] == 0.0;
  for (int a = 0; a < 3 && rest; ++a) rest = v[p][a] == 0.0;
  for (int a = 0; a < 3 && rest; ++a)
    for (int b = 0; b < 3 && rest; ++b) rest = sigma[p](a, b) == 0.0;
  return rest;
}

}  // namespace

std::vector<char> MpmSolver::idle_points() const {
  const Index n = points_.size();
  if (n == 0) return {};
  // Points that enter at this step's start are not in the store yet: their reach is not known.
  if (pts_.activation_due(time_)) return {};
  // Loaded bodies' points are never idle (a load may act on them within the step), nor are points
  // whose material changes by its own clock (an explosive lit by the program burn).
  std::vector<char> loaded(scenario_.bodies.size(), 0);
  for (const LoadSpec& load : scenario_.loads)
    for (std::size_t b = 0; b < scenario_.bodies.size(); ++b)
      if (load.body.empty() || load.body == scenario_.bodies[b].name) loaded[b] = 1;
  std::vector<char> self_changing;
  for (const auto& m : pts_.materials()) self_changing.push_back(m->changes_at_rest() ? 1 : 0);
  const auto* x = points_.view(kPosition);
  const auto* v = points_.view(kVelocity);
  const auto* sigma = points_.view(kStress);
  const auto* body = points_.ints(kBodyIndex);
  const auto* mat = points_.ints(kMaterialIndex);
  const double* q = bulk_viscosity_.active() ? points_.real(kBulkViscosity) : nullptr;
  std::vector<char> resting(static_cast<std::size_t>(n), 0);
  bool any_resting = false, any_moving = false;
  for (Index p = 0; p < n; ++p) {
    const bool rest = !loaded[static_cast<std::size_t>(body[p])] &&
                      !self_changing[static_cast<std::size_t>(mat[p])] && at_rest(v, sigma, q, p);
    resting[static_cast<std::size_t>(p)] = rest;
    any_resting = any_resting || rest;
    any_moving = any_moving || !rest;
  }
  if (!any_resting || !any_moving) return {};
  // Distances in the coarsest level's cells (the grid's own without patches): a patch's cells,
  // and the split lines its faces draw across the grid, are no wider.
  const GridGeometry& g = level_geom_.empty() ? grid_.geom : level_geom_.front();
  int cells[3] = {1, 1, 1};
  for (int a = 0; a < dim_; ++a) cells[a] = g.nodes[a] - 1;
  auto cell_of = [&](const Vec3& at) {
    std::size_t c = 0;
    for (int a = dim_ - 1; a >= 0; --a)
      c = c * static_cast<std::size_t>(cells[a]) + static_cast<std::size_t>(std::clamp(g.cell_of(at[a], a), 0, cells[a] - 1));
    return c;
  };
  const std::size_t ncells = static_cast<std::size_t>(cells[0]) * cells[1] * cells[2];
  std::vector<char> occupied(ncells, 0), reached(ncells, 0);
  std::vector<std::size_t> cell(static_cast<std::size_t>(n));
  // A moving point carries a change along its path, through cells empty at the step's start. Each
  // substep moves it less than cfl l_p |v| / (c + |v|) (its own Courant step bounds the substep),
  // under that many of the coarsest cells; over R substeps, twice that at its speed at the step's
  // start, a margin for its speed changing within the step (check_idle_points_rest stops a run
  // whose point outran it). The path's cells count as reached and occupied.
  const double cfl = scenario_.simulation.cfl;
  std::map<int, std::vector<char>> paths;  // by the path's length in cells: the cells it starts from
  for (Index p = 0; p < n; ++p) {
    const std::size_t c = cell_of(x[p]);
    cell[static_cast<std::size_t>(p)] = c;
    occupied[c] = 1;
    if (resting[static_cast<std::size_t>(p)]) continue;
    reached[c] = 1;
    const double speed = norm(v[p]), c_p = wave_scratch_.size() > static_cast<std::size_t>(p) ? wave_scratch_[p] : 0.0;
    const double share = speed > 0.0 ? speed / (c_p + speed) : 0.0;
    const int path = static_cast<int>(std::ceil(2.0 * multirate_max_ * cfl * share));
    if (path <= 0) continue;
    std::vector<char>& from = paths[path];
    if (from.empty()) from.assign(ncells, 0);
    from[c] = 1;
  }
  for (auto& [path, from] : paths) {
    dilate(from, cells, dim_, path);
    for (std::size_t c = 0; c < ncells; ++c)
      if (from[c]) reached[c] = occupied[c] = 1;
  }
  // Two hops per substep, each to the occupied cells within reach: the points a point shares nodes
  // with (2 stencil_reach cells), a hanging node's masters (1), and the path within its substep of
  // a point set moving by the change (1: under a cell per substep, CFL < 1).
  const int hop = 2 * stencil_reach(shape_) + 2;
  std::vector<char> before;
  for (int k = 0; k < 2 * multirate_max_; ++k) {
    before = reached;
    dilate(reached, cells, dim_, hop);
    for (std::size_t c = 0; c < ncells; ++c) reached[c] = reached[c] && occupied[c];
    if (reached == before) break;
  }
  std::vector<char> idle(static_cast<std::size_t>(n), 0);
  bool any_idle = false;
  for (Index p = 0; p < n; ++p) {
    const std::size_t i = static_cast<std::size_t>(p);
    idle[i] = resting[i] && !reached[cell[i]];
    any_idle = any_idle || idle[i];
  }
  if (!any_idle) return {};
  return idle;
}

void MpmSolver::check_idle_points_rest() const {
  // An idle point took its step, whatever its length, on the promise that nothing reaches it
  // within it: it must end it at rest and stress-free. One that does not shows the reach bound
  // wrong; the run stops rather than carry a point stepped past its stable step.
  const auto* v = points_.view(kVelocity);
  const auto* sigma = points_.view(kStress);
  const auto* id = points_.ints(kId);
  const double* q = bulk_viscosity_.active() ? points_.real(kBulkViscosity) : nullptr;
  for (Index p = 0; p < points_.size(); ++p)
    if (std::binary_search(idle_ids_.begin(), idle_ids_.end(), id[p]) && !at_rest(v, sigma, q, p))
      throw std::logic_error(fmt::format(
          "multi-rate step {} (t = {:.6g} s): particle {} was idle (at rest, out of every moving point's reach "
          "within the step) and was moved or stressed in it: the reach bound of mpm/multirate_idle.cpp does not "
          "hold here; run without mpm.multirate and report the deck",
          steps_, time_, id[p]));
}

}  // namespace ballista
