#include "geometry/grid_axes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

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

double GridAxes::cell_size_at(int axis, double x) const {
  const std::vector<double>& n = node[axis];
  const auto c = std::clamp<std::ptrdiff_t>(std::upper_bound(n.begin(), n.end(), x) - n.begin() - 1, 0,
                                            static_cast<std::ptrdiff_t>(n.size()) - 2);
  return n[static_cast<std::size_t>(c) + 1] - n[static_cast<std::size_t>(c)];
}

GridAxes build_grid_axes(const GridSpec& g, int dim) {
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
