#include "mpm/grid_exchange.hpp"

#include <algorithm>

namespace ballista {

void GridExchange::plan(const Communicator& comm, const ActiveBlocks& blocks, Index node_count,
                        const std::vector<int>* neighbours) {
  blocks_ = &blocks;
  node_count_ = node_count;
  if (counted_.size() != static_cast<std::size_t>(node_count)) counted_.assign(node_count, 1);
  // Nodes marked as booked elsewhere in the last plan count again until this plan says otherwise.
  for (Index b : not_counted_blocks_) {
    row_start_.clear();
    row_len_.clear();
    blocks.append_rows(b, row_start_, row_len_);
    for (std::size_t r = 0; r < row_start_.size(); ++r)
      std::fill_n(counted_.begin() + row_start_[r], row_len_[r], std::uint8_t{1});
  }
  not_counted_blocks_.clear();
  peers_.clear();
  peer_blocks_.clear();
  shared_.clear();
  if (!comm.distributed()) return;
  const std::vector<Index>& mine = blocks.active_list();
  const int me = comm.rank();
  auto add_peer = [&](int r, const std::vector<Index>& theirs) {
    std::vector<Index> with;
    std::set_intersection(mine.begin(), mine.end(), theirs.begin(), theirs.end(), std::back_inserter(with));
    if (!with.empty()) {
      peers_.push_back(r);
      peer_blocks_.push_back(std::move(with));
    }
  };
  if (neighbours) {
    // The lists go to the neighbours only (sizes first, then the lists; block indices are exact
    // in doubles): O(neighbours) messages per rank, whatever the rank count.
    std::vector<int> nb(*neighbours);
    std::sort(nb.begin(), nb.end());
    std::vector<std::vector<double>> send(nb.size(), std::vector<double>{static_cast<double>(mine.size())});
    std::vector<std::vector<double>> recv(nb.size(), std::vector<double>(1));
    comm.exchange(nb, send, recv);
    for (std::size_t k = 0; k < nb.size(); ++k) {
      send[k].assign(mine.begin(), mine.end());
      recv[k].assign(static_cast<std::size_t>(recv[k][0]), 0.0);
    }
    comm.exchange(nb, send, recv);
    for (std::size_t k = 0; k < nb.size(); ++k)
      add_peer(nb[k], std::vector<Index>(recv[k].begin(), recv[k].end()));
  } else {
    // Every rank's active blocks (ascending lists, concatenated in rank order): O(active blocks of
    // all ranks) per step.
    std::vector<std::int64_t> mine64(mine.begin(), mine.end());
    std::vector<int> counts;
    const std::vector<std::int64_t> all = comm.all_gather(mine64, counts);
    std::size_t at = 0;
    for (int r = 0; r < comm.size(); ++r) {
      const auto first = all.begin() + static_cast<std::ptrdiff_t>(at);
      at += static_cast<std::size_t>(counts[r]);
      if (r != me) add_peer(r, std::vector<Index>(first, first + counts[r]));
    }
  }
  // Merge the per-peer lists into one ascending list of shared blocks with their sharers.
  std::vector<std::size_t> cursor(peers_.size(), 0);
  for (Index b : mine) {
    Shared s{b, {}};
    for (std::size_t k = 0; k < peers_.size(); ++k)
      if (cursor[k] < peer_blocks_[k].size() && peer_blocks_[k][cursor[k]] == b) {
        s.peers.push_back(static_cast<int>(k));
        ++cursor[k];
      }
    if (s.peers.empty()) continue;
    // The lowest sharer books the node work of the block.
    if (peers_[s.peers.front()] < me) {
      not_counted_blocks_.push_back(b);
      row_start_.clear();
      row_len_.clear();
      blocks.append_rows(b, row_start_, row_len_);
      for (std::size_t r = 0; r < row_start_.size(); ++r)
        std::fill_n(counted_.begin() + row_start_[r], row_len_[r], std::uint8_t{0});
    }
    shared_.push_back(std::move(s));
  }
}

void GridExchange::sum(const Communicator& comm, const std::vector<Array>& arrays, int fields) {
  last_messages_ = 0;
  last_bytes_ = 0;
  if (!comm.distributed() || peers_.empty()) return;
  // Visits the values of block b in one fixed order (field, array, row, node, component), the
  // layout of the messages.
  auto for_each_value = [&](Index b, auto&& fn) {
    row_start_.clear();
    row_len_.clear();
    blocks_->append_rows(b, row_start_, row_len_);
    for (int f = 0; f < fields; ++f)
      for (const Array& a : arrays)
        for (std::size_t r = 0; r < row_start_.size(); ++r) {
          double* base = a.data + (static_cast<std::size_t>(f) * node_count_ + row_start_[r]) * a.ncomp;
          const std::size_t len = static_cast<std::size_t>(row_len_[r]) * a.ncomp;
          for (std::size_t j = 0; j < len; ++j) fn(base[j]);
        }
  };
  const std::size_t np = peers_.size();
  send_.resize(np);
  recv_.resize(np);
  for (std::size_t k = 0; k < np; ++k) send_[k].clear();
  for (const Shared& s : shared_)
    for (int k : s.peers) for_each_value(s.block, [&](double v) { send_[k].push_back(v); });
  for (std::size_t k = 0; k < np; ++k) {
    recv_[k].resize(send_[k].size());  // the same blocks and layout both ways
    last_bytes_ += static_cast<std::int64_t>(send_[k].size() * sizeof(double));
  }
  last_messages_ = static_cast<std::int64_t>(np);
  comm.exchange(peers_, send_, recv_);
  // Totals in rank order: every sharer adds the same partials in the same order.
  const int me = comm.rank();
  std::vector<std::size_t> pos(np, 0), start(np, 0);
  std::vector<int> order;
  for (const Shared& s : shared_) {
    order.clear();  // sharers in ascending rank, -1 for this rank
    bool placed = false;
    for (int k : s.peers) {
      if (!placed && peers_[k] > me) {
        order.push_back(-1);
        placed = true;
      }
      order.push_back(k);
    }
    if (!placed) order.push_back(-1);
    std::size_t j = 0;
    for (int k : s.peers) start[k] = pos[k];
    for_each_value(s.block, [&](double& own) {
      double acc = 0.0;
      for (int k : order) acc += k < 0 ? own : recv_[k][start[k] + j];
      own = acc;
      ++j;
    });
    for (int k : s.peers) pos[k] += j;
  }
}

}  // namespace ballista
