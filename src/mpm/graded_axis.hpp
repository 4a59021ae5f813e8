#pragma once
// One axis of a graded (rectilinear) MPM grid block: node coordinates in block index order
// (ghost nodes included), the inverse cell sizes, and a lookup of the cell holding a coordinate
// in O(1): buckets no wider than the smallest cell, each holding the first cell it meets, so at
// most one step forward finds the cell. Beyond the first and last node the end cells continue.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace ballista {

struct GradedAxis {
  std::vector<double> node;      ///< coordinates, increasing, m
  std::vector<double> inv_cell;  ///< 1 / (node[c+1] - node[c]), 1/m
  double bucket_origin = 0.0, inv_bucket = 1.0;
  std::vector<int> bucket_cell;  ///< first cell meeting each bucket

  /// From node coordinates (at least two, increasing).
  explicit GradedAxis(std::vector<double> nodes = {0.0, 1.0}) : node(std::move(nodes)) {
    const int cells = static_cast<int>(node.size()) - 1;
    inv_cell.resize(static_cast<std::size_t>(cells));
    double smallest = node.back() - node.front();
    for (int c = 0; c < cells; ++c) {
      inv_cell[c] = 1.0 / (node[c + 1] - node[c]);
      smallest = std::min(smallest, node[c + 1] - node[c]);
    }
    bucket_origin = node.front();
    inv_bucket = 1.0 / smallest;
    const int buckets = static_cast<int>(std::ceil((node.back() - node.front()) * inv_bucket)) + 1;
    bucket_cell.resize(static_cast<std::size_t>(buckets));
    int c = 0;
    for (int b = 0; b < buckets; ++b) {
      const double start = bucket_origin + b * smallest;
      while (c + 1 < cells && node[c + 1] <= start) ++c;
      bucket_cell[b] = c;
    }
  }

  int cells() const { return static_cast<int>(inv_cell.size()); }
  /// Edge of cell c (beyond the ends, the end cells'), m.
  double cell_size(int c) const {
    c = std::clamp(c, 0, cells() - 1);
    return node[c + 1] - node[c];
  }

  /// Index of the cell containing x (cell c spans node[c] to node[c+1]); outside the nodes the
  /// end cells' size continues the numbering (negative below, >= cells() above).
  int cell_of(double x) const {
    if (x < node.front()) return static_cast<int>(std::floor((x - node.front()) * inv_cell.front()));
    if (x >= node.back()) return cells() + static_cast<int>(std::floor((x - node.back()) * inv_cell.back()));
    const int b =
        std::min(static_cast<int>((x - bucket_origin) * inv_bucket), static_cast<int>(bucket_cell.size()) - 1);
    int c = bucket_cell[b];
    while (c + 1 < cells() && x >= node[c + 1]) ++c;
    return c;
  }

  /// Cell index and offset t = (x - node[c]) / (node[c+1] - node[c]) in [0,1) (the end cells'
  /// sizes continue beyond the nodes).
  void locate(double x, int& c, double& t) const {
    assert(std::isfinite(x) && "non-finite particle position");
    c = cell_of(x);
    const int k = std::clamp(c, 0, cells() - 1);
    const double x0 = c < 0 ? node.front() + c * cell_size(0)
                            : (c >= cells() ? node.back() + (c - cells()) * cell_size(cells() - 1) : node[c]);
    t = (x - x0) * inv_cell[k];
  }

  /// Node coordinate of index i (beyond the ends, the end cells' sizes continue).
  double at(int i) const {
    if (i < 0) return node.front() + i * cell_size(0);
    if (i >= static_cast<int>(node.size())) return node.back() + (i - cells()) * cell_size(cells() - 1);
    return node[i];
  }
};

/// A box's node coordinates continued by `ghost` cells of its end cells' size on either side: how
/// the MPM grid lays out a graded axis.
inline std::vector<double> with_ghost_layers(const std::vector<double>& box, int ghost) {
  const double first = box[1] - box[0], last = box.back() - box[box.size() - 2];
  std::vector<double> nodes;
  for (int k = ghost; k > 0; --k) nodes.push_back(box.front() - k * first);
  nodes.insert(nodes.end(), box.begin(), box.end());
  for (int k = 1; k <= ghost; ++k) nodes.push_back(box.back() + k * last);
  return nodes;
}

}  // namespace ballista
