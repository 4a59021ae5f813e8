// The reference gas family with a coarser gas lattice (peridynamics/bond_family.hpp,
// build_gas_family with `scale`; a body's point_spacing): products seeded on a lattice twice as
// coarse as the solid beside them. Against brute force: the pairs are exactly those of the rule
// (two gas points within the smaller of their horizons scale x delta, a gas point and a solid within
// the gas point's), with the partial volume of the finer end's spacing; and the density measure
// stays what makes the gas a pressure: under a uniform dilatation lambda every gas point reads
// X = lambda^d, whatever its family (the measure is normalised by the point's own family volume).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "peridynamics/bond_family.hpp"
#include "peridynamics/gas_pass.hpp"

namespace ballista::test_gas_family {
namespace {

TEST(GasFamily, CoarseGasLatticeBesideAFineSolid) {
  for (int dim : {2, 3}) {
    // Solid: spacing 1 over x in (0, 6); gas: spacing 2 over x in (-10, 0); both over y (and z)
    // in (0, 12). delta = 3 on the solid's lattice, so the gas's horizon is 6.
    const double dx = 1.0, delta = 3.0, a = 2.0;
    std::vector<Vec3> x;
    std::vector<std::uint8_t> gas;
    std::vector<double> scale, vol0;
    const int nz_s = dim == 3 ? 12 : 1, nz_g = dim == 3 ? 6 : 1;
    for (int k = 0; k < nz_g; ++k)
      for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 5; ++i) {
          x.push_back(Vec3{{-a * (i + 0.5), a * (j + 0.5), dim == 3 ? a * (k + 0.5) : 0.0}});
          gas.push_back(1);
          scale.push_back(a);
          vol0.push_back(std::pow(a * dx, dim));
        }
    for (int k = 0; k < nz_s; ++k)
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 6; ++i) {
          x.push_back(Vec3{{i + 0.5, j + 0.5, dim == 3 ? k + 0.5 : 0.0}});
          gas.push_back(0);
          scale.push_back(1.0);
          vol0.push_back(std::pow(dx, dim));
        }
    const Index n = static_cast<Index>(x.size());
    const pd::BondFamily f = pd::build_gas_family(x.data(), n, delta, dx, dim, gas.data(), scale.data());
    ASSERT_EQ(f.points(), n);

    // Brute force: pair -> (length, partial-volume factor).
    std::map<std::pair<Index, Index>, std::pair<double, double>> expected, listed;
    for (Index p = 0; p < n; ++p)
      for (Index q = 0; q < n; ++q) {
        if (p == q || !(gas[p] || gas[q])) continue;
        const double R = gas[p] && gas[q] ? delta * std::min(scale[p], scale[q]) : delta * (gas[p] ? scale[p] : scale[q]);
        const double h = dx * std::min(scale[p], scale[q]);  // the finer end's spacing
        Vec3 y = x[q] - x[p];
        if (dim == 2) y[2] = 0.0;
        const double r = norm(y);
        if (r > R * (1.0 + 1e-9)) continue;
        const double w = pd::partial_volume_factor(r, R, h);
        if (w > 0.0) expected[{p, q}] = {r, w};
      }
    for (Index p = 0; p < n; ++p)
      for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) listed[{p, f.other[k]}] = {f.length0[k], f.volume_factor[k]};
    ASSERT_EQ(listed.size(), expected.size()) << dim;
    int solid_pairs = 0;
    for (const auto& [pq, lw] : expected) {
      const auto it = listed.find(pq);
      ASSERT_NE(it, listed.end()) << dim << ": pair " << pq.first << "-" << pq.second << " missing";
      EXPECT_NEAR(it->second.first, lw.first, 1e-12) << dim;
      EXPECT_NEAR(it->second.second, lw.second, 1e-6) << dim;  // stored as a float
      solid_pairs += !gas[pq.first] || !gas[pq.second];
    }
    // The coarse gas reaches 6 solid spacings into the solid: more than its own horizon would.
    EXPECT_GT(solid_pairs, 0);
    double deepest = 0.0;
    for (const auto& [pq, lw] : expected)
      if (gas[pq.first] && !gas[pq.second]) deepest = std::max(deepest, x[pq.second][0]);
    EXPECT_GT(deepest, delta) << dim;

    // A uniform dilatation lambda: every gas point (interior, surface, next to the solid) reads
    // X = lambda^d.
    const double lambda = 1.3;
    std::vector<Vec3> xs(x);
    for (Vec3& y : xs) y = lambda * y;
    std::vector<double> V(static_cast<size_t>(n), 0.0), g(static_cast<size_t>(n), 0.0);
    for (Index p = 0; p < n; ++p)
      for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) V[p] += f.volume_factor[k] * vol0[f.other[k]];
    const pd::GasPassArgs args{xs.data(), vol0.data(), &f, gas.data(), V.data(), g.data(), dim};
    for (Index p = 0; p < n; ++p)
      if (gas[p]) {
        EXPECT_NEAR(pd::density_measure(args, p), std::pow(lambda, dim), 1e-12) << dim << " point " << p;
      }
  }
}

}  // namespace
}  // namespace ballista::test_gas_family
