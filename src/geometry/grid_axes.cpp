#include "geometry/grid_axes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "core/error.hpp"

namespace ballista {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

[[noreturn]] void zone_error(const RefineZone& z, const std::string& key, const std::string& message) {
  throw DeckError(z.mark.file, z.mark.line, z.mark.column, z.mark.key_path + (key.empty() ? "" : "." + key), message);
}

/// Cells filling a gap of length L between a cell of size hl (left; kInf: a box face, no
/// constraint) and one of size hr (right), none larger than H, neighbouring ratios at most q.
/// For n cells, cell i can be at most M_i = min(hl q^i, hr q^(n+1-i), H) and at least
/// m_i = max(hl q^-i, hr q^-(n+1-i)); both sequences keep every neighbouring ratio within q, and
/// so does their geometric blend s_i = m_i^(1-a) M_i^a for any a in [0,1] (the log of the
/// ratio is a convex combination). The fewest cells with sum m <= L <= sum M are taken, a found
/// by bisection so that the cells sum to L. Empty if no n fits.
std::vector<double> fill_gap(double L, double hl, double hr, double H, double q) {
  const double lq = std::log(q);
  const double small = std::min(hl, hr);
  const int ramp = static_cast<int>(std::ceil(std::log(H / small) / lq)) + 1;
  const int n0 = std::max(1, static_cast<int>(std::floor(L / H)) - 2 * ramp - 2);
  const int n_max = static_cast<int>(std::ceil(L / (small / q))) + 2;
  std::vector<double> m, M;
  for (int n = n0; n <= n_max; ++n) {
    m.assign(static_cast<std::size_t>(n), 0.0);
    M.assign(static_cast<std::size_t>(n), H);
    double sum_m = 0.0, sum_M = 0.0;
    bool ok = true;
    for (int i = 1; i <= n; ++i) {
      double hi = H, lo = 0.0;
      if (std::isfinite(hl)) {
        hi = std::min(hi, hl * std::pow(q, i));
        lo = std::max(lo, hl * std::pow(q, -i));
      }
      if (std::isfinite(hr)) {
        hi = std::min(hi, hr * std::pow(q, n + 1 - i));
        lo = std::max(lo, hr * std::pow(q, -(n + 1 - i)));
      }
      if (!std::isfinite(hl) && !std::isfinite(hr)) lo = H;
      if (lo > hi * (1.0 + 1e-12)) ok = false;
      m[i - 1] = std::min(lo, hi);
      M[i - 1] = hi;
      sum_m += m[i - 1];
      sum_M += M[i - 1];
    }
    if (!ok || sum_M < L) continue;
    if (sum_m > L) break;  // more cells only raise the smallest possible sum: nothing fits
    auto blend = [&](double a, std::vector<double>& out) {
      out.resize(m.size());
      double sum = 0.0;
      for (std::size_t i = 0; i < m.size(); ++i)
        sum += (out[i] = m[i] > 0.0 ? std::pow(m[i], 1.0 - a) * std::pow(M[i], a) : a * M[i]);
      return sum;
    };
    std::vector<double> cells;
    double a0 = 0.0, a1 = 1.0;
    for (int it = 0; it < 200; ++it) {
      const double a = 0.5 * (a0 + a1);
      (blend(a, cells) < L ? a0 : a1) = a;
    }
    const double sum = blend(0.5 * (a0 + a1), cells);
    for (double& c : cells) c *= L / sum;  // the last round-off
    return cells;
  }
  return {};
}

/// Appends the nodes of cells `sizes` after `nodes.back()`, the last exactly at `end`.
void append_cells(std::vector<double>& nodes, const std::vector<double>& sizes, double end) {
  double x = nodes.back();
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    x += sizes[k];
    nodes.push_back(k + 1 == sizes.size() ? end : x);
  }
}

const char* axis_letter(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

std::vector<double> graded_axis(const GridSpec& g, int a, std::vector<RefineZone> zones) {
  std::sort(zones.begin(), zones.end(), [](const RefineZone& p, const RefineZone& q) { return p.from < q.from; });
  const double lo = g.lower[a], hi = g.upper[a], H = g.cell_size, q = g.grading;
  for (std::size_t k = 0; k < zones.size(); ++k) {
    const RefineZone& z = zones[k];
    if (!(z.from >= lo && z.to <= hi))
      zone_error(z, "", fmt::format("the zone {:g} to {:g} m lies outside the grid's {} range {:g} to {:g} m", z.from,
                                    z.to, axis_letter(a), lo, hi));
    if (k > 0 && z.from < zones[k - 1].to)
      zone_error(z, "from",
                 fmt::format("the zone overlaps another zone along {} ({} from {:g} to {:g} m)", axis_letter(a),
                             zones[k - 1].mark.key_path, zones[k - 1].from, zones[k - 1].to));
  }
  std::vector<double> nodes{lo};
  double prev_cell = kInf;  // the cell before the current gap (kInf: the box face)
  double at = lo;
  auto fill = [&](double end, double next_cell, const RefineZone* next) {
    const double L = end - at;
    if (L <= 0.0) {
      if (std::isfinite(prev_cell) && std::isfinite(next_cell) &&
          std::max(prev_cell / next_cell, next_cell / prev_cell) > q * (1.0 + 1e-9))
        zone_error(*next, "from",
                   fmt::format("zones of {:.4g} and {:.4g} m cells meet at {} = {:g} m: a ratio of {:.3g} between "
                               "neighbouring cells, more than grid.grading = {:g}; leave room between them to grade",
                               prev_cell, next_cell, axis_letter(a), at,
                               std::max(prev_cell / next_cell, next_cell / prev_cell), q));
      return;
    }
    const std::vector<double> cells = fill_gap(L, prev_cell, next_cell, H, q);
    if (cells.empty()) {
      const RefineZone& z = next ? *next : zones.back();
      zone_error(z, next ? "from" : "to",
                 fmt::format("the {:g} m between {} = {:g} and {:g} m is too short to grade from {:.4g} to {:.4g} m "
                             "cells with grid.grading = {:g}: move the zone, or raise grid.grading",
                             L, axis_letter(a), at, end, std::isfinite(prev_cell) ? prev_cell : H,
                             std::isfinite(next_cell) ? next_cell : H, q));
    }
    append_cells(nodes, cells, end);
  };
  for (const RefineZone& z : zones) {
    const int n = static_cast<int>(std::ceil((z.to - z.from) / z.cell_size - 1e-9));
    const double cell = (z.to - z.from) / n;
    fill(z.from, cell, &z);
    for (int k = 1; k <= n; ++k) nodes.push_back(k == n ? z.to : z.from + k * cell);
    at = z.to;
    prev_cell = cell;
  }
  fill(hi, kInf, nullptr);
  return nodes;
}

}  // namespace

double GridAxes::smallest(int axis) const {
  double s = kInf;
  for (std::size_t k = 0; k + 1 < node[axis].size(); ++k) s = std::min(s, node[axis][k + 1] - node[axis][k]);
  return s;
}

double GridAxes::largest(int axis) const {
  double s = 0.0;
  for (std::size_t k = 0; k + 1 < node[axis].size(); ++k) s = std::max(s, node[axis][k + 1] - node[axis][k]);
  return s;
}

namespace {

/// The size of the cell of `n` holding x (beyond the ends, the end cell's).
double size_of_cell_holding(const std::vector<double>& n, double x) {
  const auto c = std::clamp<std::ptrdiff_t>(std::upper_bound(n.begin(), n.end(), x) - n.begin() - 1, 0,
                                            static_cast<std::ptrdiff_t>(n.size()) - 2);
  return n[static_cast<std::size_t>(c) + 1] - n[static_cast<std::size_t>(c)];
}

}  // namespace

double GridAxes::cell_size_at(int axis, double x) const { return size_of_cell_holding(node[axis], x); }

bool PatchBox::strictly_contains(const Vec3& x, int dim) const {
  for (int a = 0; a < dim; ++a) {
    if (!open_lower[a] && !(x[a] > lower[a])) return false;
    if (!open_upper[a] && !(x[a] < upper[a])) return false;
  }
  return true;
}

bool PatchBox::holds(const Vec3& x, int dim) const {
  for (int a = 0; a < dim; ++a) {
    if (!open_lower[a] && !(x[a] >= lower[a])) return false;
    if (!open_upper[a] && !(x[a] < upper[a])) return false;
  }
  return true;
}

int GridAxes::innermost_holding(const Vec3& x, int dim) const {
  int best = -1;
  for (std::size_t k = 0; k < patches.size(); ++k)
    if (patches[k].holds(x, dim) && (best < 0 || patches[k].depth > patches[static_cast<std::size_t>(best)].depth))
      best = static_cast<int>(k);
  return best;
}

int GridAxes::innermost_containing(const Vec3& x, int dim) const {
  int best = -1;
  for (std::size_t k = 0; k < patches.size(); ++k)
    if (patches[k].strictly_contains(x, dim) &&
        (best < 0 || patches[k].depth > patches[static_cast<std::size_t>(best)].depth))
      best = static_cast<int>(k);
  return best;
}

const std::vector<double>& GridAxes::lattice_of(int patch, int axis) const {
  return patch < 0 ? base[axis] : patches[static_cast<std::size_t>(patch)].lattice[axis];
}

double GridAxes::effective_cell_size(int axis, const Vec3& x, int dim) const {
  return size_of_cell_holding(lattice_of(innermost_holding(x, dim), axis), x[axis]);
}

namespace {

[[noreturn]] void patch_error(const GridPatch& p, const std::string& key, const std::string& message) {
  throw DeckError(p.mark.file, p.mark.line, p.mark.column, p.mark.key_path + (key.empty() ? "" : "." + key), message);
}

/// The node of `nodes` at x (within a millionth of the neighbouring cells), or -1.
int node_at(const std::vector<double>& nodes, double x) {
  const auto it = std::lower_bound(nodes.begin(), nodes.end(), x);
  const std::ptrdiff_t k = it - nodes.begin();
  for (std::ptrdiff_t c : {k - 1, k}) {
    if (c < 0 || c >= static_cast<std::ptrdiff_t>(nodes.size())) continue;
    const std::size_t u = static_cast<std::size_t>(c);
    const double near = std::min(u > 0 ? nodes[u] - nodes[u - 1] : kInf, u + 1 < nodes.size() ? nodes[u + 1] - nodes[u] : kInf);
    if (std::abs(nodes[u] - x) <= 1e-6 * near) return static_cast<int>(c);
  }
  return -1;
}

/// Whether box a holds box b along the first `dim` axes (faces may touch).
bool box_holds(const GridPatch& a, const GridPatch& b, int dim) {
  for (int d = 0; d < dim; ++d)
    if (!(a.lower[d] <= b.lower[d] && b.upper[d] <= a.upper[d])) return false;
  return true;
}

bool boxes_overlap(const GridPatch& a, const GridPatch& b, int dim) {
  for (int d = 0; d < dim; ++d)
    if (!(a.lower[d] < b.upper[d] && b.lower[d] < a.upper[d])) return false;
  return true;
}

/// Sorted union of node lists, a node within a billionth of its cell of one before it dropped.
std::vector<double> merge_nodes(const std::vector<const std::vector<double>*>& lists) {
  std::vector<double> all;
  for (const std::vector<double>* l : lists) all.insert(all.end(), l->begin(), l->end());
  std::sort(all.begin(), all.end());
  const double tol = all.empty() ? 0.0 : 1e-12 * (all.back() - all.front());
  std::vector<double> out;
  for (const double x : all)
    if (out.empty() || x - out.back() > tol) out.push_back(x);
  return out;
}

/// Checks the patches (against the grid, against their parents' cells and against each other) and
/// returns their boxes with nesting depth, parent and lattice. A patch lies either inside another
/// (nested: its faces on its parent's split nodes, its cells finer than the parent's) or apart
/// from it; two patches apart that share a range along an axis split it alike, so that a patch's
/// split lines never cut another's cells where neither lies inside the other.
std::vector<PatchBox> patch_boxes(const GridSpec& g, int dim, const std::array<std::vector<double>, 3>& base) {
  const std::size_t np = g.patches.size();
  std::vector<PatchBox> boxes(np);
  for (std::size_t i = 0; i < np; ++i) {
    const GridPatch& p = g.patches[i];
    for (int a = 0; a < dim; ++a) {
      if (!(p.upper[a] > p.lower[a]))
        patch_error(p, "upper", fmt::format("expected upper > lower along {}, got {:g} and {:g} m", axis_letter(a),
                                            p.upper[a], p.lower[a]));
      for (const auto& [x, key] : {std::pair{p.lower[a], "lower"}, std::pair{p.upper[a], "upper"}})
        if (x < base[a].front() - 1e-9 * (base[a].back() - base[a].front()) ||
            x > base[a].back() + 1e-9 * (base[a].back() - base[a].front()))
          patch_error(p, key, fmt::format("{} = {:g} m lies outside the grid ({:g} to {:g} m)", axis_letter(a), x,
                                          base[a].front(), base[a].back()));
    }
    // Nesting: the depth is one more than the patches holding it; the parent is the deepest.
    boxes[i].depth = 1;
    for (std::size_t j = 0; j < np; ++j) {
      if (j == i) continue;
      const GridPatch& q = g.patches[j];
      const bool q_holds = box_holds(q, p, dim), p_holds = box_holds(p, q, dim);
      if (q_holds && p_holds)
        patch_error(p, "", fmt::format("the patch is the same box as {}", q.mark.key_path));
      if (!q_holds && !p_holds && boxes_overlap(p, q, dim))
        patch_error(p, "", fmt::format("the patch overlaps {} without lying inside it or holding it: patches nest "
                                       "or lie apart",
                                       q.mark.key_path));
      if (q_holds) ++boxes[i].depth;
    }
  }
  for (std::size_t i = 0; i < np; ++i)
    for (std::size_t j = 0; j < np; ++j)
      if (j != i && boxes[j].depth == boxes[i].depth - 1 && box_holds(g.patches[j], g.patches[i], dim))
        boxes[i].parent = static_cast<int>(j);
  // Parents first, so that each patch splits its parent's lattice.
  std::vector<std::size_t> order(np);
  for (std::size_t i = 0; i < np; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return boxes[a].depth < boxes[b].depth; });
  for (const std::size_t i : order) {
    const GridPatch& p = g.patches[i];
    PatchBox& b = boxes[i];
    b.lower = p.lower;
    b.upper = p.upper;
    for (int a = dim; a < 3; ++a) b.lattice[a] = {0.0};
    for (int a = 0; a < dim; ++a) {
      const std::vector<double>& n = b.parent < 0 ? base[a] : boxes[static_cast<std::size_t>(b.parent)].lattice[a];
      const int lo = node_at(n, p.lower[a]), hi = node_at(n, p.upper[a]);
      for (const auto& [k, x, key] : {std::tuple{lo, p.lower[a], "lower"}, std::tuple{hi, p.upper[a], "upper"}}) {
        if (k >= 0) continue;
        const auto it = std::clamp(std::upper_bound(n.begin(), n.end(), x), n.begin() + 1, n.end() - 1);
        patch_error(p, key,
                    fmt::format("{} = {:g} m is not a node of {} (the nearest are {:g} and {:g} m): a patch's faces "
                                "lie on the nodes of the cells it splits",
                                axis_letter(a), x,
                                b.parent < 0 ? std::string("the grid")
                                             : "the patch it lies in (" + g.patches[static_cast<std::size_t>(b.parent)].mark.key_path + ")",
                                *(it - 1), *it));
      }
      // The faces are the nodes themselves (not the deck's numbers, which may differ from them in
      // the last bit), so that a node on a face is never taken for one inside.
      b.lower[a] = n[static_cast<std::size_t>(lo)];
      b.upper[a] = n[static_cast<std::size_t>(hi)];
      // A face on the grid box's face is open: the ghost layers beyond it continue the patch's cells.
      b.open_lower[static_cast<std::size_t>(a)] = b.lower[a] == base[a].front();
      b.open_upper[static_cast<std::size_t>(a)] = b.upper[a] == base[a].back();
      // A nested patch's face lies inside its parent (or on the grid box's face), so that the cells
      // across each face are split once more than the patch's own, never twice.
      if (b.parent >= 0) {
        const std::string& parent_key = g.patches[static_cast<std::size_t>(b.parent)].mark.key_path;
        for (const auto& [touch, open, x, key] :
             {std::tuple{lo == 0, b.open_lower[static_cast<std::size_t>(a)], b.lower[a], "lower"},
              std::tuple{hi == static_cast<int>(n.size()) - 1, b.open_upper[static_cast<std::size_t>(a)], b.upper[a],
                         "upper"}})
          if (touch && !open)
            patch_error(p, key,
                        fmt::format("{} = {:g} m is a face of the patch it lies in ({}): a nested patch's faces lie "
                                    "inside its parent (or on the grid's box), so that the cells across a face are "
                                    "split once more than its own, not twice",
                                    axis_letter(a), x, parent_key));
      }
      std::vector<double>& out = b.lattice[a];
      out = {n[static_cast<std::size_t>(lo)]};
      for (int c = lo; c < hi; ++c) {
        const std::size_t u = static_cast<std::size_t>(c);
        const double cell = n[u + 1] - n[u];
        if (!(p.cell_size < cell * (1.0 - 1e-9)))
          patch_error(p, "cell_size", fmt::format("expected cells finer than the {:g} m cells it splits along {} (at "
                                                  "{:g} m), got {:g} m",
                                                  cell, axis_letter(a), n[u], p.cell_size));
        const int parts = static_cast<int>(std::ceil(cell / p.cell_size - 1e-9));
        b.ratio = std::max(b.ratio, parts);
        for (int k = 1; k < parts; ++k) out.push_back(n[u] + cell * k / parts);
        out.push_back(n[u + 1]);
      }
    }
  }
  // Patches apart from each other split a range they share alike.
  for (std::size_t i = 0; i < np; ++i)
    for (std::size_t j = i + 1; j < np; ++j) {
      if (box_holds(g.patches[i], g.patches[j], dim) || box_holds(g.patches[j], g.patches[i], dim)) continue;
      for (int a = 0; a < dim; ++a) {
        const double lo = std::max(boxes[i].lower[a], boxes[j].lower[a]), hi = std::min(boxes[i].upper[a], boxes[j].upper[a]);
        if (!(hi > lo)) continue;
        auto in_range = [&](const std::vector<double>& l) {
          std::vector<double> r;
          for (const double x : l)
            if (x >= lo && x <= hi) r.push_back(x);
          return r;
        };
        const std::vector<double> ri = in_range(boxes[i].lattice[a]), rj = in_range(boxes[j].lattice[a]);
        bool same = ri.size() == rj.size();
        for (std::size_t k = 0; same && k < ri.size(); ++k) same = std::abs(ri[k] - rj[k]) <= 1e-9 * (hi - lo);
        if (!same)
          patch_error(g.patches[j], "cell_size",
                      fmt::format("its range along {} ({:g} to {:g} m) is split otherwise than by {}, which lies "
                                  "apart from it: patches apart that share a range along an axis split it alike",
                                  axis_letter(a), lo, hi, g.patches[i].mark.key_path));
      }
    }
  return boxes;
}

}  // namespace

GridAxes build_grid_axes(const GridSpec& g, int dim) {
  GridAxes axes = build_base_axes(g, dim);
  axes.base = axes.node;
  axes.level = {axes.base};
  if (g.patches.empty()) return axes;
  axes.patches = patch_boxes(g, dim, axes.base);
  int deepest = 0;
  for (const PatchBox& b : axes.patches) deepest = std::max(deepest, b.depth);
  for (int k = 1; k <= deepest; ++k) {
    std::array<std::vector<double>, 3> lv;
    for (int a = 0; a < 3; ++a) {
      std::vector<const std::vector<double>*> lists{&axes.base[a]};
      if (a < dim)
        for (const PatchBox& b : axes.patches)
          if (b.depth <= k) lists.push_back(&b.lattice[a]);
      lv[a] = a < dim ? merge_nodes(lists) : axes.base[a];
    }
    axes.level.push_back(std::move(lv));
  }
  axes.node = axes.level.back();
  return axes;
}

GridAxes build_base_axes(const GridSpec& g, int dim) {
  GridAxes axes;
  for (int a = 0; a < 3; ++a) {
    if (a >= dim) {
      axes.node[a] = {0.0};
      continue;
    }
    std::vector<RefineZone> zones;
    for (const RefineZone& z : g.refine) {
      if (z.axis != a) continue;
      if (!(z.cell_size < g.cell_size))
        zone_error(z, "cell_size", fmt::format("expected cells finer than grid.cell_size = {:g} m, got {:g} m",
                                               g.cell_size, z.cell_size));
      if (!(z.to > z.from)) zone_error(z, "to", fmt::format("expected to > from ({:g} m), got {:g} m", z.from, z.to));
      zones.push_back(z);
    }
    if (zones.empty()) {
      // As the uniform grid: whole cells of cell_size from lower, the last node at or beyond upper.
      const int cells = static_cast<int>(std::ceil((g.upper[a] - g.lower[a]) / g.cell_size - 1e-9));
      for (int k = 0; k <= cells; ++k) axes.node[a].push_back(g.lower[a] + k * g.cell_size);
    } else {
      axes.node[a] = graded_axis(g, a, zones);
    }
  }
  return axes;
}

}  // namespace ballista
