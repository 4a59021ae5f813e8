#pragma once
// Sums over the nodes' influence domains that are bitwise those of one rank on any number of ranks.
//
// Every OTM node sum (lumped mass and force, the stable step's bounds, the F-bar's nodal averages,
// the contact's node forces, projections of the points' momentum) is a fold over a node's points
// in the serial run's point order: acc = {}; acc = fold(acc, entry) for each entry of the node's
// influence domain. Floating-point addition is not associative, so adding the ranks' partial sums
// (what an MPI reduction does) gives other bits than the serial fold. Here instead:
//   - a node whose points are all on one rank (most nodes) is folded there, entry by entry, as the
//     serial run folds it;
//   - a node reached by the points of several ranks ("shared") is folded by the lowest of them,
//     from every such rank's entries merged in the points' id order (the serial run's point order:
//     ids follow the points' places while bodies arriving later come after the others in the
//     deck), with the same fold;
//   - each node's result goes from the rank that folded it to every rank (every rank holds every
//     node: docs/parallel.md).
// The fold is one function for both paths, fed the same inputs, and it writes each multiply-add
// as a fused one (add_product, std::fma): the build lets GCC fuse a * b + c where it sees fit
// (-ffp-contract=fast), and which product it fuses in a * b + c * d, or whether it fuses at all,
// depends on the code the fold is inlined into; written out, the bits cannot depend on the path.
// This is the exact analogue of peridynamics' ghosts: the inputs move, the arithmetic does not.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/communicator.hpp"
#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "otm/otm_support.hpp"

namespace ballista::otm {

/// Which ranks' points reach each node (rebuilt with the influence domains; every rank takes part).
class NodeSharing {
 public:
  static constexpr int kNone = -2;    ///< no rank's points reach the node
  static constexpr int kShared = -1;  ///< the points of several ranks reach it

  /// From each rank's influence domains over nn nodes (two all-reduces of nn integers).
  void update(const Communicator& comm, const Influences& inf, Index nn);
  /// The one rank whose points reach node a, kShared or kNone.
  int holder(Index a) const { return holder_[static_cast<std::size_t>(a)]; }
  /// The rank that folds node a: the lowest rank whose points reach it.
  int reducer(Index a) const { return reducer_[static_cast<std::size_t>(a)]; }

 private:
  std::vector<int> holder_, reducer_;
};

/// What a node fold reads: the influence domains, the points' global ids and the sharing.
struct NodeFoldScope {
  const Communicator* comm = nullptr;     ///< null or one rank: the serial fold only
  const Influences* inf = nullptr;
  const std::int64_t* id = nullptr;       ///< each point's global id (several ranks)
  const NodeSharing* sharing = nullptr;   ///< several ranks
  Index nodes = 0;
};

/// acc += a b with one rounding, whatever code surrounds it (a node fold's multiply-add).
inline void add_product(double& acc, double a, double b) { acc = std::fma(a, b, acc); }
inline void add_product(Vec3& acc, double a, const Vec3& b) {
  for (int c = 0; c < 3; ++c) acc[c] = std::fma(a, b[c], acc[c]);
}

namespace detail {

/// Every rank's results, (node, record of `bytes`) as doubles in `mine`, into records[node].
void gather_results(const Communicator& comm, const std::vector<double>& mine, std::size_t bytes, void* records);

}  // namespace detail

/// out[a] = the fold over node a's entries i (inf.start[a] <= i < inf.start[a + 1], the points in
/// increasing order) with input(i, in) true, for the nodes with wanted(a); Acc{} for the others.
/// In and Acc are plain structs of doubles; fold(acc, in) writes its multiply-adds with add_product.
/// Every rank calls it alike (several ranks: collective).
template <class Acc, class In, class Wanted, class Input, class Fold>
void fold_nodes(const NodeFoldScope& s, std::vector<Acc>& out, Wanted wanted, Input input, Fold fold) {
  static_assert(std::is_trivially_copyable_v<Acc> && sizeof(Acc) % sizeof(double) == 0);
  static_assert(std::is_trivially_copyable_v<In>);
  const Index nn = s.nodes;
  const Influences& inf = *s.inf;
  out.assign(static_cast<std::size_t>(nn), Acc{});
  for_each_heavy(0, nn, [&](Index a) {
    if (!wanted(a)) return;
    Acc acc{};
    In in;
    for (Index i = inf.start[a]; i < inf.start[a + 1]; ++i)
      if (input(i, in)) fold(acc, in);
    out[static_cast<std::size_t>(a)] = acc;
  });
  if (s.comm == nullptr || !s.comm->distributed()) return;

  const Communicator& comm = *s.comm;
  const int R = comm.size(), me = comm.rank();
  const NodeSharing& sh = *s.sharing;
  struct Entry {
    std::int64_t node, id;
    In in;
  };
  // A shared node's entries go to its reducer (the lowest rank whose points reach it).
  // Buffers kept from call to call (their pages stay mapped: a fresh large allocation costs a page
  // fault per page at every step).
  static std::vector<std::vector<Entry>> to;
  to.resize(static_cast<std::size_t>(R));
  for (auto& list : to) list.clear();
  for (Index a = 0; a < nn; ++a) {
    if (sh.holder(a) != NodeSharing::kShared || inf.start[a + 1] == inf.start[a] || !wanted(a)) continue;
    std::vector<Entry>& list = to[static_cast<std::size_t>(sh.reducer(a))];
    In in;
    for (Index i = inf.start[a]; i < inf.start[a + 1]; ++i)
      if (input(i, in)) list.push_back(Entry{a, s.id[inf.owner[i]], in});
  }
  static std::vector<std::vector<char>> send, got;
  send.resize(static_cast<std::size_t>(R));
  for (int r = 0; r < R; ++r) {
    if (r == me) continue;
    const std::vector<Entry>& list = to[static_cast<std::size_t>(r)];
    send[static_cast<std::size_t>(r)].resize(list.size() * sizeof(Entry));
    if (!list.empty()) std::memcpy(send[static_cast<std::size_t>(r)].data(), list.data(), list.size() * sizeof(Entry));
  }
  comm.all_to_all(send, got);
  // Each source's entries (this rank's and every other's) come node by node, in increasing node
  // and, within a node, increasing id: merged, they are the node's entries in id order.
  for (int r = 0; r < R; ++r) {
    if (r == me) continue;
    const std::vector<char>& b = got[static_cast<std::size_t>(r)];
    std::vector<Entry>& list = to[static_cast<std::size_t>(r)];
    list.resize(b.size() / sizeof(Entry));
    if (!list.empty()) std::memcpy(static_cast<void*>(list.data()), b.data(), list.size() * sizeof(Entry));
  }
  std::vector<std::size_t> at(static_cast<std::size_t>(R), 0);
  for (;;) {
    std::int64_t a = std::numeric_limits<std::int64_t>::max();
    for (int r = 0; r < R; ++r)
      if (at[r] < to[r].size()) a = std::min(a, to[r][at[r]].node);
    if (a == std::numeric_limits<std::int64_t>::max()) break;
    Acc acc{};
    for (;;) {
      int next = -1;
      for (int r = 0; r < R; ++r)
        if (at[r] < to[r].size() && to[r][at[r]].node == a && (next < 0 || to[r][at[r]].id < to[next][at[next]].id))
          next = r;
      if (next < 0) break;
      fold(acc, to[next][at[next]++].in);
    }
    out[static_cast<std::size_t>(a)] = acc;
  }
  // Every rank gets the nodes each rank holds alone or folded.
  constexpr std::size_t per = sizeof(Acc) / sizeof(double);
  std::vector<double> mine;
  for (Index a = 0; a < nn; ++a) {
    const int h = sh.holder(a);
    if (!wanted(a) || !(h == me || (h == NodeSharing::kShared && sh.reducer(a) == me))) continue;
    const std::size_t k = mine.size();
    mine.resize(k + 1 + per);
    mine[k] = static_cast<double>(a);
    std::memcpy(mine.data() + k + 1, &out[static_cast<std::size_t>(a)], sizeof(Acc));
  }
  detail::gather_results(comm, mine, sizeof(Acc), out.data());
}

}  // namespace ballista::otm
