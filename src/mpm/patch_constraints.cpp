#include "mpm/patch_constraints.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <unordered_map>
#include <utility>

namespace ballista {

namespace {

/// Per node of one axis of the grid, against one lattice (a patch's own nodes or the grid's
/// without the splits): whether it is a lattice node (or outside the lattice's range, or a ghost)
/// and, if not, the grid indices of the lattice nodes around it and its linear weights.
struct AxisSplit {
  std::vector<char> on;
  std::vector<int> lo, hi;
  std::vector<double> w_lo, w_hi;
};

AxisSplit split_of_axis(const GradedAxis& ax, int nodes, const std::vector<double>& lattice,
                        int ghost) {
  AxisSplit s;
  const std::size_t n = static_cast<std::size_t>(nodes);
  s.on.assign(n, 1);
  s.lo.assign(n, -1);
  s.hi.assign(n, -1);
  s.w_lo.assign(n, 0.0);
  s.w_hi.assign(n, 0.0);
  // The grid index of each lattice node (every lattice node is a grid node).
  std::vector<int> at;
  int i = ghost;
  for (const double xl : lattice) {
    const double tol = 1e-9 * (lattice.back() - lattice.front());
    while (i < nodes - ghost && ax.at(i) < xl - tol) ++i;
    at.push_back(i);
  }
  for (std::size_t m = 0; m + 1 < at.size(); ++m)
    for (int k = at[m] + 1; k < at[m + 1]; ++k) {
      const std::size_t u = static_cast<std::size_t>(k);
      s.on[u] = 0;
      s.lo[u] = at[m];
      s.hi[u] = at[m + 1];
      const double xl = ax.at(at[m]), xh = ax.at(at[m + 1]), x = ax.at(k);
      s.w_hi[u] = (x - xl) / (xh - xl);
      s.w_lo[u] = (xh - x) / (xh - xl);
    }
  return s;
}

}  // namespace

PatchConstraints::PatchConstraints(const GridGeometry& g, const GridAxes& axes, int ghost) {
  if (axes.patches.empty() || !g.graded) return;
  const int dim = g.dim;
  const std::size_t regions =
      axes.patches.size() + 1;  // region r: patch r - 1, or 0 the grid's own cells
  std::vector<std::array<AxisSplit, 3>> split(regions);
  for (std::size_t r = 0; r < regions; ++r)
    for (int a = 0; a < dim; ++a)
      split[r][static_cast<std::size_t>(a)] = split_of_axis(
          (*g.graded)[a], g.nodes[a], axes.lattice_of(static_cast<int>(r) - 1, a), ghost);

  // The direct masters of a node (empty: free), on the lattice of the region it lies in.
  auto direct = [&](int i, int j, int k) {
    std::vector<std::pair<Index, double>> out;
    const int ijk[3] = {i, j, k};
    const std::array<AxisSplit, 3>& base = split[0];
    bool on_base = true;
    for (int a = 0; a < dim; ++a)
      on_base = on_base && base[static_cast<std::size_t>(a)].on[static_cast<std::size_t>(ijk[a])];
    if (on_base) return out;  // the grid's own nodes lie on every patch's lattice
    const std::size_t r =
        static_cast<std::size_t>(axes.innermost_containing(g.node_position(i, j, k), dim) + 1);
    int splits[3], ns = 0;
    for (int a = 0; a < dim; ++a)
      if (!split[r][static_cast<std::size_t>(a)].on[static_cast<std::size_t>(ijk[a])])
        splits[ns++] = a;
    for (int m = 0; m < (ns > 0 ? 1 << ns : 0); ++m) {
      int at[3] = {i, j, k};
      double w = 1.0;
      for (int q = 0; q < ns; ++q) {
        const int a = splits[q];
        const AxisSplit& s = split[r][static_cast<std::size_t>(a)];
        const std::size_t u = static_cast<std::size_t>(ijk[a]);
        const bool upper = (m >> q) & 1;
        at[a] = upper ? s.hi[u] : s.lo[u];
        w *= upper ? s.w_hi[u] : s.w_lo[u];
      }
      out.emplace_back(g.node_index(at[0], at[1], at[2]), w);
    }
    return out;
  };

  // Composed to free masters (memoised: a face's hanging nodes share their masters).
  std::unordered_map<Index, std::vector<std::pair<Index, double>>> resolved;
  auto ijk_of = [&](Index n, int out[3]) {
    out[0] = static_cast<int>(n % g.nodes[0]);
    out[1] = static_cast<int>((n / g.nodes[0]) % g.nodes[1]);
    out[2] = static_cast<int>(n / (static_cast<Index>(g.nodes[0]) * g.nodes[1]));
  };
  std::function<std::vector<std::pair<Index, double>>(Index)> resolve = [&](Index n) {
    if (auto it = resolved.find(n); it != resolved.end()) return it->second;
    int c[3];
    ijk_of(n, c);
    const std::vector<std::pair<Index, double>> d = direct(c[0], c[1], c[2]);
    std::map<Index, double> sum;
    if (d.empty()) {
      sum[n] = 1.0;
    } else {
      for (const auto& [m, w] : d)
        for (const auto& [f, v] : resolve(m)) sum[f] += w * v;
    }
    std::vector<std::pair<Index, double>> out(sum.begin(), sum.end());
    resolved.emplace(n, out);
    return out;
  };

  for (int k = 0; k < g.nodes[2]; ++k)
    for (int j = 0; j < g.nodes[1]; ++j)
      for (int i = 0; i < g.nodes[0]; ++i) {
        if (direct(i, j, k).empty()) continue;
        const Index node = g.node_index(i, j, k);
        Hanging h;
        h.node = node;
        h.first = static_cast<int>(master_.size());
        int lo[3] = {i, j, k}, hi[3] = {i, j, k};
        for (const auto& [m, w] : resolve(node)) {
          if (w == 0.0) continue;
          master_.push_back(m);
          weight_.push_back(w);
          int c[3];
          ijk_of(m, c);
          for (int a = 0; a < dim; ++a) {
            lo[a] = std::min(lo[a], c[a]);
            hi[a] = std::max(hi[a], c[a]);
          }
        }
        for (int a = 0; a < dim; ++a) reach_ = std::max(reach_, hi[a] - lo[a]);
        h.count = static_cast<int>(master_.size()) - h.first;
        hanging_.push_back(h);
      }
}

}  // namespace ballista
