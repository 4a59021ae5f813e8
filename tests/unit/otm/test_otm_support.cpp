// The supports picked from the candidate lists (Verlet lists) are the supports of the binned
// search, node for node and weight for weight, whether the lists are kept or searched again.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "otm/otm_support.hpp"

namespace ballista::otm {
namespace {

struct Cloud {
  std::vector<Vec3> nodes, points;
  std::vector<std::int64_t> node_body, point_body;
};

/// Nodes on a jittered lattice of spacing h in two bodies (halves of the box), points at the
/// cell centres.
Cloud make_cloud(int n, double h, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.1 * h, 0.1 * h);
  Cloud c;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        c.nodes.push_back(Vec3{{i * h + jitter(rng), j * h + jitter(rng), k * h + jitter(rng)}});
        c.node_body.push_back(i < n / 2 ? 0 : 1);
        if (i + 1 < n && j + 1 < n && k + 1 < n) {
          c.points.push_back(Vec3{{(i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h}});
          c.point_body.push_back(i + 1 < n / 2 ? 0 : 1);
        }
      }
  return c;
}

/// The options of a 3D lattice of spacing h (gamma and tolerance the defaults).
SupportOptions options_3d(double h) {
  SupportOptions opt;
  opt.h = h;
  opt.dim = 3;
  return opt;
}

void expect_same(const Supports& a, const Supports& b) {
  ASSERT_EQ(a.offset, b.offset);
  ASSERT_EQ(a.node, b.node);
  ASSERT_EQ(a.N, b.N);  // bitwise: the same nodes in the same order give the same solve
  for (size_t k = 0; k < a.dN.size(); ++k)
    for (int d = 0; d < 3; ++d) ASSERT_EQ(a.dN[k][d], b.dN[k][d]);
}

TEST(OtmSupportCandidates, TheSameSupportsAsTheSearchWhileKeptAndWhenSearchedAgain) {
  std::mt19937 rng(7);
  const double h = 1.0e-3;
  Cloud c = make_cloud(8, h, rng);
  const SupportOptions opt = options_3d(h);
  const Index np = static_cast<Index>(c.points.size()), nn = static_cast<Index>(c.nodes.size());
  std::vector<double> scale(static_cast<size_t>(np), 1.0);
  std::vector<Vec3> lambda_a(static_cast<size_t>(np)), lambda_b(static_cast<size_t>(np));
  SupportCandidates lists;
  std::uniform_real_distribution<double> step(-1.0, 1.0);
  const double r0 = support_radius(opt);
  // Small moves (the lists are kept) and, every eighth step, a move past the margin (searched
  // again); stretches up to 1.1 widen the radius.
  for (int s = 0; s < 24; ++s) {
    const double size = s % 8 == 7 ? 0.3 * r0 : 0.004 * r0;
    for (Vec3& x : c.nodes)
      for (int d = 0; d < 3; ++d) x[d] += size * step(rng);
    for (Vec3& x : c.points)
      for (int d = 0; d < 3; ++d) x[d] += size * step(rng);
    for (double& f : scale) f = 1.0 + 0.1 * (0.5 + 0.5 * step(rng));
    Supports searched, listed;
    build_supports(c.points.data(), c.point_body.data(), np, c.nodes.data(), c.node_body.data(), nn, opt,
                   scale.data(), nullptr, lambda_a.data(), searched);
    build_supports(c.points.data(), c.point_body.data(), np, c.nodes.data(), c.node_body.data(), nn, opt,
                   scale.data(), nullptr, lambda_b.data(), listed, &lists);
    expect_same(searched, listed);
  }
  // Kept between the small moves, searched again after each large one (and at the start): the
  // test would pass trivially if the lists were searched every step.
  EXPECT_GE(lists.searches, 4);
  EXPECT_LT(lists.searches, 24);
}

TEST(OtmSupportCandidates, SearchedAgainWhenTheNodesChange) {
  std::mt19937 rng(11);
  const double h = 1.0e-3;
  Cloud c = make_cloud(6, h, rng);
  const SupportOptions opt = options_3d(h);
  const Index np = static_cast<Index>(c.points.size());
  std::vector<Vec3> lambda(static_cast<size_t>(np));
  SupportCandidates lists;
  Supports sup;
  auto build = [&] {
    build_supports(c.points.data(), c.point_body.data(), np, c.nodes.data(), c.node_body.data(),
                   static_cast<Index>(c.nodes.size()), opt, nullptr, nullptr, lambda.data(), sup, &lists);
  };
  build();
  build();
  EXPECT_EQ(lists.searches, 1);  // nothing moved
  c.node_body[0] = 1 - c.node_body[0];
  build();
  EXPECT_EQ(lists.searches, 2);  // a node changed body
  c.nodes.push_back(c.nodes.back());
  c.node_body.push_back(c.node_body.back());
  build();
  EXPECT_EQ(lists.searches, 3);  // a node was added
}

}  // namespace
}  // namespace ballista::otm
