#pragma once
// The blocks of the MPM grid that particles can reach this step (the sparse grid): the
// grid is cut into blocks of kBlock^dim nodes; a block is active if some particle's stencil (its
// cell widened by the shape function's reach) or a traction point's stencil overlaps it. Only
// active blocks are zeroed and updated, so empty space in the box costs one flag per block.
// Nodes outside the active blocks are kept at zero (a block that falls inactive is cleared
// once), exactly what a dense pass would leave there, so results do not change by a bit.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "mpm/grid_geometry.hpp"

namespace ballista {

class ActiveBlocks {
 public:
  static constexpr int kBlock = 8;  ///< nodes per block and axis

  /// Sets the block layout of grid `g` (all inactive).
  void reset(const GridGeometry& g);
  /// Marks the blocks overlapping nodes [c - reach, c + 1 + reach] of each point's cell c
  /// (points outside the grid are clamped to it: the solver reports them).
  void mark(const Vec3* x, Index n, int reach);
  /// Ends marking: the node rows of the active blocks (ascending), and the rows of the blocks that
  /// were active before and are not now (released(): the caller clears them).
  void finish();

  Index rows() const { return static_cast<Index>(row_start_.size()); }
  /// Calls f(i) for every node i of the active blocks, node index + `offset` (one velocity field's
  /// offset), in parallel over rows. Each node is visited once.
  template <class F>
  void for_each_node(Index offset, F&& f) const {
    if (dense_) {
      for_each(offset, offset + g_.node_count(), f);
      return;
    }
    for_each(0, rows(), [&](Index r) {
      const Index b = row_start_[r] + offset;
      for (Index i = b; i < b + row_len_[r]; ++i) f(i);
    });
  }
  /// Calls f(begin, end) for every run of consecutive active nodes [begin, end) (+ `offset`), in
  /// parallel: for passes the compiler should vectorise (zeroing).
  template <class F>
  void for_each_run(Index offset, F&& f) const {
    if (dense_) {
      const Index n = g_.node_count();
      const Index chunk = 4096;
      for_each_chunk((n + chunk - 1) / chunk,
                     [&](Index c) { f(offset + c * chunk, offset + std::min(n, (c + 1) * chunk)); });
      return;
    }
    for_each(0, rows(), [&](Index r) { f(row_start_[r] + offset, row_start_[r] + offset + row_len_[r]); });
  }
  /// Same over the blocks released by the last finish().
  template <class F>
  void for_each_released_node(Index offset, F&& f) const {
    for_each(0, static_cast<Index>(released_start_.size()), [&](Index r) {
      const Index b = released_start_[r] + offset;
      for (Index i = b; i < b + released_len_[r]; ++i) f(i);
    });
  }
  Index active_blocks() const { return static_cast<Index>(active_list_.size()); }
  /// The active blocks of the last finish(), ascending.
  const std::vector<Index>& active_list() const { return active_list_; }
  /// Several ranks, before finish(): also marks the mirror image, across the node plane `face` of
  /// `axis`, of every marked block within `band` nodes of it, so that a rank holding a ghost node
  /// beyond a mirror face also holds its image inside and the other way round (the fold of
  /// MpmSolver::fold_mirror_faces then sees the same summed values on every rank).
  void mark_mirror_images(int axis, int face, int band);
  /// Rows (x-runs of nodes) of block b appended to start/len.
  void append_rows(Index b, std::vector<Index>& start, std::vector<int>& len) const;
  Index block_count() const { return static_cast<Index>(flag_.size()); }
  /// The block holding node (i, j, k).
  Index block_of(int i, int j, int k) const {
    return (static_cast<Index>(k / kBlock) * nb_[1] + j / kBlock) * nb_[0] + i / kBlock;
  }
  /// More than kDenseFraction of the nodes active: the node passes run over the whole grid.
  bool dense() const { return dense_; }
  static constexpr double kDenseFraction = 0.5;

 private:

  GridGeometry g_;
  int nb_[3] = {1, 1, 1};              ///< blocks per axis
  std::vector<std::uint8_t> flag_;     ///< per block: marked this step
  std::vector<Index> active_list_;     ///< active blocks, ascending
  std::vector<Index> row_start_;       ///< first node of each row of the active blocks
  std::vector<int> row_len_;           ///< its node count
  std::vector<Index> released_start_;  ///< rows of the blocks released by the last finish()
  std::vector<int> released_len_;
  Index active_nodes_ = 0;
  bool dense_ = true;
};

}  // namespace ballista
