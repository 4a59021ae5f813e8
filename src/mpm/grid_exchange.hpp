#pragma once
// The MPM grid across ranks. Every rank keeps the node layout of the whole grid but
// touches only the blocks its particles reach (mpm/active_blocks.hpp). A block reached by the
// particles of several ranks is shared: after each particle-to-grid pass the sharers exchange
// their partial nodal sums of that block and each adds them in rank order, so every sharer holds
// bitwise the same totals and the node passes that follow (velocities, boundary conditions,
// contact) give the same values on every sharer without another message. The halo is therefore
// as wide as the particles' stencils reach (a block of 8 nodes per axis is the unit sent).
// Work booked at nodes (damping, contact) counts a shared node on its lowest sharer only.
#include <cstdint>
#include <vector>

#include "core/communicator.hpp"
#include "mpm/active_blocks.hpp"

namespace ballista {

class GridExchange {
 public:
  /// One node array to sum: `ncomp` doubles per node, field after field (fields x nodes).
  struct Array {
    double* data;
    int ncomp;
  };

  /// Which ranks share each of this rank's active blocks (collective; after ActiveBlocks::finish).
  /// With `neighbours` (the ranks whose regions come near this one's, the same relation on every
  /// rank) the active-block lists go only to them; without, every rank's list to every rank.
  void plan(const Communicator& comm, const ActiveBlocks& blocks, Index node_count,
            const std::vector<int>* neighbours = nullptr);
  /// Sums the arrays over the sharers of every shared block, in rank order (collective).
  void sum(const Communicator& comm, const std::vector<Array>& arrays, int fields);
  /// Per node: 0 for the nodes of blocks shared with a lower rank (which books their work), else 1.
  const std::uint8_t* counted() const { return counted_.data(); }
  /// Messages and bytes this rank sent in the last sum() (the halo, for the scaling model).
  std::int64_t last_messages() const { return last_messages_; }
  std::int64_t last_bytes() const { return last_bytes_; }
  /// Blocks shared with at least one other rank in the last plan().
  Index shared_blocks() const { return static_cast<Index>(shared_.size()); }

 private:
  struct Shared {
    Index block;
    std::vector<int> peers;  ///< indices into peers_ of the other sharers, ascending rank
  };
  std::vector<int> peers_;                    ///< ranks sharing at least one block, ascending
  std::vector<std::vector<Index>> peer_blocks_;  ///< per peer: the shared blocks, ascending
  std::vector<Shared> shared_;                ///< this rank's shared blocks, ascending
  std::vector<std::uint8_t> counted_;         ///< per node
  std::vector<Index> not_counted_blocks_;     ///< blocks whose nodes are 0 in counted_
  const ActiveBlocks* blocks_ = nullptr;
  Index node_count_ = 0;
  std::vector<Index> row_start_;  ///< scratch: rows of one block
  std::vector<int> row_len_;
  std::vector<std::vector<double>> send_, recv_;
  std::int64_t last_messages_ = 0, last_bytes_ = 0;
};

}  // namespace ballista
