// CellBins::visit_within against visit: the pruned visit skips only bins with no point within the
// radius, so the points within the radius come out the same and in the same order (the renewed gas
// family and the contact list depend on that order for bitwise results). Random clouds in 2D and
// 3D, queries inside and outside the box, reaches 1-3; the comparison is exact (no tolerance: it
// is a filter of the same sequence).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "points/cell_bins.hpp"

namespace ballista::test_cell_bins {
namespace {

std::vector<Index> within(const CellBins& bins, const Vec3* x, const Vec3& y, double radius, int reach, int dim,
                          bool pruned) {
  std::vector<Index> out;
  auto take = [&](Index q) {
    Vec3 d = x[q] - y;
    if (dim == 2) d[2] = 0.0;
    if (dot(d, d) <= radius * radius) out.push_back(q);
  };
  if (pruned)
    bins.visit_within(y, radius, take, reach);
  else
    bins.visit(y, take, reach);
  return out;
}

TEST(CellBins, VisitWithinFindsWhatVisitFindsInTheSameOrder) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int dim : {2, 3}) {
    std::vector<Vec3> x(4000);
    for (auto& p : x) p = Vec3{{u(rng), 0.5 * u(rng), dim == 3 ? 0.7 * u(rng) : 0.0}};
    const double size = 0.11;
    const CellBins bins(x.data(), static_cast<Index>(x.size()), size, dim);
    long found = 0, visited_all = 0, visited_pruned = 0;
    for (int reach = 1; reach <= 3; ++reach)
      for (int k = 0; k < 300; ++k) {
        // Queries up to 30 % beyond the box (clamped into the edge bins) and the largest radius
        // the reach allows.
        const Vec3 y{{1.3 * u(rng), 0.65 * u(rng), dim == 3 ? 0.9 * u(rng) : 0.0}};
        const double radius = reach * bins.size() * (k % 2 == 0 ? 1.0 : 0.6);
        const auto a = within(bins, x.data(), y, radius, reach, dim, false);
        const auto b = within(bins, x.data(), y, radius, reach, dim, true);
        ASSERT_EQ(a, b) << "dim " << dim << " reach " << reach << " query " << k;
        found += static_cast<long>(a.size());
        bins.visit(y, [&](Index) { ++visited_all; }, reach);
        bins.visit_within(y, radius, [&](Index) { ++visited_pruned; }, reach);
      }
    EXPECT_GT(found, 0);
    // The point of the pruning: fewer candidates (a sphere fills ~half its box of bins in 3D).
    EXPECT_LT(visited_pruned, visited_all) << "dim " << dim;
  }
}

}  // namespace
}  // namespace ballista::test_cell_bins
