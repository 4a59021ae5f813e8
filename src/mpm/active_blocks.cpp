#include "mpm/active_blocks.hpp"

#include <algorithm>
#include <atomic>

namespace ballista {

void ActiveBlocks::reset(const GridGeometry& g) {
  g_ = g;
  for (int a = 0; a < 3; ++a) nb_[a] = (g.nodes[a] + kBlock - 1) / kBlock;
  flag_.assign(static_cast<std::size_t>(nb_[0]) * nb_[1] * nb_[2], 0);
  active_list_.clear();
  row_start_.clear();
  row_len_.clear();
  released_start_.clear();
  released_len_.clear();
}

void ActiveBlocks::mark(const Vec3* x, Index n, int reach) {
  const int nd = g_.dim;
  std::uint8_t* flag = flag_.data();
  // Points come sorted by cell (MpmSolver::sort_by_cell), and neighbouring cells mostly reach the
  // same blocks (eight cells a block along x), so a run of points marks its blocks once: each
  // chunk remembers the last range of blocks it marked.
  constexpr Index kChunk = kPointChunk;  // the common split of the point passes
  const Index chunks = (n + kChunk - 1) / kChunk;
  for_each_point_chunk(chunks, [&](Index ch) {
    int last_lo[3] = {-1, -1, -1}, last_hi[3] = {-1, -1, -1};
    for (Index p = ch * kChunk; p < std::min(n, (ch + 1) * kChunk); ++p) {
      int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
      for (int a = 0; a < nd; ++a) {
        const int c = std::clamp(g_.cell_of(x[p][a], a), 0, g_.nodes[a] - 1);
        lo[a] = std::max(c - reach, 0) / kBlock;
        hi[a] = std::min(c + 1 + reach, g_.nodes[a] - 1) / kBlock;
      }
      if (std::equal(lo, lo + 3, last_lo) && std::equal(hi, hi + 3, last_hi)) continue;
      std::copy(lo, lo + 3, last_lo);
      std::copy(hi, hi + 3, last_hi);
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int i = lo[0]; i <= hi[0]; ++i) {
            // Relaxed atomic store: many points mark the same block; all store 1.
            std::atomic_ref<std::uint8_t> f(flag[(static_cast<Index>(k) * nb_[1] + j) * nb_[0] + i]);
            if (f.load(std::memory_order_relaxed) == 0) f.store(1, std::memory_order_relaxed);
          }
    }
  });
}

void ActiveBlocks::mark_mirror_images(int axis, int face, int band) {
  const int nba = nb_[axis];
  int bc[3];
  for (bc[2] = 0; bc[2] < nb_[2]; ++bc[2])
    for (bc[1] = 0; bc[1] < nb_[1]; ++bc[1])
      for (bc[0] = 0; bc[0] < nb_[0]; ++bc[0]) {
        const Index b = (static_cast<Index>(bc[2]) * nb_[1] + bc[1]) * nb_[0] + bc[0];
        if (!flag_[static_cast<std::size_t>(b)]) continue;
        // Node range of the block on the axis, cut to the band around the face.
        const int lo = std::max(bc[axis] * kBlock, face - band);
        const int hi = std::min(std::min((bc[axis] + 1) * kBlock, g_.nodes[axis]) - 1, face + band);
        if (lo > hi) continue;
        const int mlo = std::max(2 * face - hi, 0), mhi = std::min(2 * face - lo, g_.nodes[axis] - 1);
        for (int m = mlo / kBlock; m <= mhi / kBlock && m < nba; ++m) {
          int c[3] = {bc[0], bc[1], bc[2]};
          c[axis] = m;
          flag_[static_cast<std::size_t>((static_cast<Index>(c[2]) * nb_[1] + c[1]) * nb_[0] + c[0])] = 1;
        }
      }
}

void ActiveBlocks::append_rows(Index b, std::vector<Index>& start, std::vector<int>& len) const {
  const int bi = static_cast<int>(b % nb_[0]);
  const int bj = static_cast<int>((b / nb_[0]) % nb_[1]);
  const int bk = static_cast<int>(b / (static_cast<Index>(nb_[0]) * nb_[1]));
  const int i0 = bi * kBlock, i1 = std::min(i0 + kBlock, g_.nodes[0]);
  const int j1 = std::min((bj + 1) * kBlock, g_.nodes[1]);
  const int k1 = std::min((bk + 1) * kBlock, g_.nodes[2]);
  for (int k = bk * kBlock; k < k1; ++k)
    for (int j = bj * kBlock; j < j1; ++j) {
      start.push_back(g_.node_index(i0, j, k));
      len.push_back(i1 - i0);
    }
}

void ActiveBlocks::finish() {
  // Released: active in the previous list, not flagged now.
  released_start_.clear();
  released_len_.clear();
  for (Index b : active_list_)
    if (!flag_[static_cast<std::size_t>(b)]) append_rows(b, released_start_, released_len_);
  active_list_.clear();
  row_start_.clear();
  row_len_.clear();
  for (Index b = 0; b < static_cast<Index>(flag_.size()); ++b)
    if (flag_[static_cast<std::size_t>(b)]) {
      active_list_.push_back(b);
      append_rows(b, row_start_, row_len_);
      flag_[static_cast<std::size_t>(b)] = 0;  // ready for the next step's marking
    }
  active_nodes_ = 0;
  for (int len : row_len_) active_nodes_ += len;
  // Mostly active: one contiguous pass over every node is cheaper than short rows, and gives the
  // same values (the inactive nodes are zero and stay zero through the node passes).
  dense_ = active_nodes_ > kDenseFraction * static_cast<double>(g_.node_count());
}


}  // namespace ballista
