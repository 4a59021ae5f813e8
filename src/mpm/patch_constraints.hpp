#pragma once
// The hanging nodes of a grid with patches (grid.patches): boxes of finer cells inside coarser
// ones, which may nest. The grid is the tensor product of each axis's nodes, so a patch's split
// lines cross the whole grid; where a node lies off the lattice of the region it is in (the
// deepest patch strictly containing it, or the grid's own cells outside every patch) it is tied to
// that lattice's nodes around it by linear interpolation, u_s = sum_m w_sm u_m (the hanging-node
// constraint of h-refined finite elements, as in the structured mesh refinement of GIMP, Ma, Lu &
// Komanduri, CMES 12 (2006) 213). A master on a patch's face may hang in turn (on the parent's
// lattice); the constraints are composed until every master is free, which ends because each
// step goes to a coarser region. The basis that remains is N_m + sum_s w_sm N_s for each free node
// m: each region's own cells' hats, continuous across the faces, so the partition of unity and
// the reproduction of linear fields hold everywhere. The transfers stay those of the tensor grid:
// after the particles map to it, each hanging node's sums go to its masters with its weights
// (fold), and after the grid update each hanging node takes its masters' interpolated value
// (fill).
#include <vector>

#include "core/tensor.hpp"
#include "geometry/grid_axes.hpp"
#include "mpm/grid_geometry.hpp"

namespace ballista {

class PatchConstraints {
 public:
  /// A hanging node and its free masters, masters() of them from first() in master()/weight().
  struct Hanging {
    Index node = 0;
    int first = 0;
    int count = 0;
  };

  PatchConstraints() = default;
  /// The hanging nodes of grid `g` (its graded axes with `ghost` layers each side of the box
  /// `axes`); ghost nodes continue the box's end cells and never hang.
  PatchConstraints(const GridGeometry& g, const GridAxes& axes, int ghost);

  bool empty() const { return hanging_.empty(); }
  const std::vector<Hanging>& hanging() const { return hanging_; }
  Index master(const Hanging& h, int k) const {
    return master_[static_cast<std::size_t>(h.first + k)];
  }
  double weight(const Hanging& h, int k) const {
    return weight_[static_cast<std::size_t>(h.first + k)];
  }
  /// The most cells a hanging node and its masters span along an axis: how far the blocks a
  /// point's stencil reaches must be widened so that its masters are in them.
  int reach() const { return reach_; }

  /// Moves the sums of each hanging node of field block `a` (node count `nodes`, `fields` blocks)
  /// to its masters: a_m += w a_s, then a_s = 0. Every master is free, so the order is immaterial.
  template <class T>
  void fold(T* a, Index nodes, int fields) const {
    for (int f = 0; f < fields; ++f) {
      T* b = a + f * nodes;
      for (const Hanging& h : hanging_) {
        const T s = b[h.node];
        for (int k = 0; k < h.count; ++k) b[master(h, k)] += weight(h, k) * s;
        b[h.node] = T{};
      }
    }
  }
  /// Sets each hanging node of every field block to its masters' interpolated value.
  template <class T>
  void fill(T* a, Index nodes, int fields) const {
    for (int f = 0; f < fields; ++f) {
      T* b = a + f * nodes;
      for (const Hanging& h : hanging_) {
        T s{};
        for (int k = 0; k < h.count; ++k) s += weight(h, k) * b[master(h, k)];
        b[h.node] = s;
      }
    }
  }

 private:
  std::vector<Hanging> hanging_;
  std::vector<Index> master_;
  std::vector<double> weight_;
  int reach_ = 0;
};

}  // namespace ballista
