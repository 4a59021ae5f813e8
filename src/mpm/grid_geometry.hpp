#pragma once
// Geometry of a block of the MPM background grid. Node indices are relative to the block origin
// so that an MPI rank can own one block (with ghost layers) without changing any kernel. A
// uniform grid has cubic cells of size h; a graded grid (grid.refine) has per-axis node
// coordinates (mpm/graded_axis.hpp), and h is then its smallest cell.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "mpm/graded_axis.hpp"

namespace ballista {

struct GridGeometry {
  Vec3 origin;               ///< position of node (0,0,0) of this block, m
  double h = 1.0;            ///< cell size, m (cubic cells); a graded grid's smallest cell
  int nodes[3] = {1, 1, 1};  ///< node counts per axis (nodes[2] = 1 in 2D)
  int dim = 3;               ///< 2 or 3
  /// Graded grids: each axis's node coordinates (block index order); null for a uniform grid.
  std::shared_ptr<const std::array<GradedAxis, 3>> graded;

  Index node_count() const { return static_cast<Index>(nodes[0]) * nodes[1] * nodes[2]; }
  Index node_index(int i, int j, int k) const {
    return (static_cast<Index>(k) * nodes[1] + j) * nodes[0] + i;
  }
  /// Index of the cell containing coordinate x along `axis` (cell c spans nodes c and c+1).
  int cell_of(double x, int axis) const {
    if (graded) return (*graded)[axis].cell_of(x);
    return static_cast<int>(std::floor((x - origin[axis]) / h));
  }
  Vec3 node_position(int i, int j, int k) const {
    if (graded)
      return {{(*graded)[0].at(i), (*graded)[1].at(j), dim == 3 ? (*graded)[2].at(k) : origin[2]}};
    return {{origin[0] + i * h, origin[1] + j * h, dim == 3 ? origin[2] + k * h : origin[2]}};
  }
  /// Edge of cell c along `axis`, m.
  double cell_size(int c, int axis) const { return graded ? (*graded)[axis].cell_size(c) : h; }
  /// The volume a full node stands for (in the units of the particle volumes: per unit thickness in
  /// 2D, per radian in axisymmetric): per axis half of each neighbouring cell, and in axisymmetric
  /// the radial part weighted by r (the integral of r dr over the node's half cells, from the axis
  /// at r = 0). For a region the particles fill, sum_p N_I V_p equals it (partition of unity).
  double node_volume(Index node, bool axisymmetric) const {
    const int ijk[3] = {static_cast<int>(node % nodes[0]), static_cast<int>((node / nodes[0]) % nodes[1]),
                        static_cast<int>(node / (static_cast<Index>(nodes[0]) * nodes[1]))};
    double v = 1.0;
    for (int a = 0; a < dim; ++a) {
      const double below = 0.5 * cell_size(ijk[a] - 1, a), above = 0.5 * cell_size(ijk[a], a);
      if (a == 0 && axisymmetric) {
        const double r = node_position(ijk[0], ijk[1], ijk[2])[0];
        const double lo = std::max(r - below, 0.0), hi = r + above;
        v *= 0.5 * (hi * hi - lo * lo);
      } else {
        v *= below + above;
      }
    }
    return v;
  }
};

}  // namespace ballista
