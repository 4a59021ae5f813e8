// Node sums bitwise those of one rank on any number of ranks (node_sums.hpp).
#include "otm/node_sums.hpp"

namespace ballista::otm {

void NodeSharing::update(const Communicator& comm, const Influences& inf, Index nn) {
  holder_.clear();
  reducer_.clear();
  if (!comm.distributed()) return;
  // Per node: how many ranks' points reach it, and the lowest such rank (as ranks - rank, a max).
  const int ranks = comm.size(), me = comm.rank();
  std::vector<std::int64_t> count(static_cast<std::size_t>(nn), 0), lowest(static_cast<std::size_t>(nn), 0);
  for (Index a = 0; a < nn; ++a)
    if (inf.start[a + 1] > inf.start[a]) {
      count[static_cast<std::size_t>(a)] = 1;
      lowest[static_cast<std::size_t>(a)] = ranks - me;
    }
  comm.sum(count.data(), static_cast<int>(nn));
  comm.max(lowest.data(), static_cast<int>(nn));
  holder_.resize(static_cast<std::size_t>(nn));
  reducer_.resize(static_cast<std::size_t>(nn));
  for (Index a = 0; a < nn; ++a) {
    const std::size_t i = static_cast<std::size_t>(a);
    const int first = static_cast<int>(ranks - lowest[i]);
    holder_[i] = count[i] == 0 ? kNone : count[i] == 1 ? first : kShared;
    reducer_[i] = count[i] == 0 ? 0 : first;
  }
}

namespace detail {

void gather_results(const Communicator& comm, const std::vector<double>& mine, std::size_t bytes, void* records) {
  std::vector<int> counts;
  const std::vector<double> all = comm.all_gather_reals(mine, counts);
  const std::size_t per = 1 + bytes / sizeof(double);
  auto* base = static_cast<char*>(records);
  for (std::size_t k = 0; k + per <= all.size(); k += per)
    std::memcpy(base + static_cast<std::size_t>(all[k]) * bytes, all.data() + k + 1, bytes);
}

}  // namespace detail
}  // namespace ballista::otm
