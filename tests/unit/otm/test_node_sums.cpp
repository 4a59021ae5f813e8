// The node sums of OTM (src/otm/node_sums.hpp) on one rank, on synthetic supports:
//  - each node's sum is the fold over its points in increasing point order, to the bit (what the
//    several-rank path reproduces from every rank's inputs merged in id order): checked against
//    a scatter over the points in their order with the same fused multiply-adds;
//  - nodes not wanted are zero, entries the input rejects are skipped (not added as zero);
//  - the result does not depend on the thread count (bitwise).
// The sums are compared byte for byte: the claim is bitwise, so no tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/parallel.hpp"
#include "otm/node_sums.hpp"

namespace ballista::otm::test_node_sums {
namespace {

struct Case {
  Supports sup;
  Influences inf;
  std::vector<double> mass;
  std::vector<Vec3> v;
  Index nodes = 600;  // above the threshold from which the node loop runs on several threads
};

/// 4,000 points, each on 6-12 of 600 nodes (increasing node index within a point, as the support
/// search gives them), weights and values spread over several decades so that the order of the
/// additions shows in the last bits.
Case make_case() {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Case c;
  const Index n = 4000;
  c.sup.offset.push_back(0);
  for (Index p = 0; p < n; ++p) {
    const int k = 6 + static_cast<int>(u(rng) * 7.0);
    const int first = static_cast<int>(u(rng) * static_cast<double>(c.nodes - k));
    for (int j = 0; j < k; ++j) {
      c.sup.node.push_back(first + j);
      c.sup.N.push_back(std::pow(10.0, -3.0 * u(rng)));
      c.sup.dN.push_back(Vec3{{u(rng), u(rng), u(rng)}});
    }
    c.sup.offset.push_back(static_cast<Index>(c.sup.node.size()));
    c.mass.push_back(std::pow(10.0, -6.0 + 2.0 * u(rng)));
    c.v.push_back(Vec3{{100.0 * u(rng) - 50.0, 300.0 * u(rng), -7.0 * u(rng)}});
  }
  build_influences(c.sup, c.nodes, c.inf);
  return c;
}

struct In {
  double N, m;
  Vec3 v;
};
struct Acc {
  double m;
  Vec3 mom;
};

void fold(Acc& acc, const In& in) {
  add_product(acc.m, in.N, in.m);
  add_product(acc.mom, in.N * in.m, in.v);
}

std::vector<Acc> folded(const Case& c, const std::vector<char>& wanted, Index skip_point) {
  NodeFoldScope scope;
  scope.inf = &c.inf;
  scope.nodes = c.nodes;
  std::vector<Acc> out;
  fold_nodes<Acc, In>(
      scope, out, [&](Index a) { return wanted[static_cast<std::size_t>(a)] != 0; },
      [&](Index i, In& in) {
        const Index p = c.inf.owner[i];
        if (p == skip_point) return false;
        in = In{c.sup.N[c.inf.entry[i]], c.mass[p], c.v[p]};
        return true;
      },
      fold);
  return out;
}

TEST(NodeSums, EachNodeIsTheFoldOverItsPointsInPointOrder) {
  const Case c = make_case();
  std::vector<char> wanted(static_cast<std::size_t>(c.nodes), 1);
  wanted[7] = 0;
  const Index skip = 1234;
  const std::vector<Acc> out = folded(c, wanted, skip);
  // The same sums as a scatter over the points in their order.
  std::vector<Acc> ref(static_cast<std::size_t>(c.nodes), Acc{});
  for (Index p = 0; p < c.sup.size(); ++p) {
    if (p == skip) continue;
    for (Index k = c.sup.offset[p]; k < c.sup.offset[p + 1]; ++k) {
      const Index a = c.sup.node[k];
      if (!wanted[static_cast<std::size_t>(a)]) continue;
      fold(ref[static_cast<std::size_t>(a)], In{c.sup.N[k], c.mass[p], c.v[p]});
    }
  }
  ASSERT_EQ(out.size(), ref.size());
  for (Index a = 0; a < c.nodes; ++a)
    EXPECT_EQ(std::memcmp(&out[static_cast<std::size_t>(a)], &ref[static_cast<std::size_t>(a)], sizeof(Acc)), 0)
        << "node " << a;
  // The unwanted node is zero; the skipped point left its nodes' sums (a node it reaches differs
  // from the sum with it).
  EXPECT_EQ(out[7].m, 0.0);
  const std::vector<Acc> with_all = folded(c, wanted, -1);
  const Index a_skip = c.sup.node[c.sup.offset[skip]];
  EXPECT_NE(out[static_cast<std::size_t>(a_skip)].m, with_all[static_cast<std::size_t>(a_skip)].m);
}

TEST(NodeSums, ResultsDoNotDependOnTheThreadCount) {
  const Case c = make_case();
  const std::vector<char> wanted(static_cast<std::size_t>(c.nodes), 1);
  const int threads = max_threads();
  set_threads(1);
  const std::vector<Acc> one = folded(c, wanted, -1);
  set_threads(2);
  const std::vector<Acc> two = folded(c, wanted, -1);
  set_threads(threads);
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(Acc)), 0);
}

}  // namespace
}  // namespace ballista::otm::test_node_sums
