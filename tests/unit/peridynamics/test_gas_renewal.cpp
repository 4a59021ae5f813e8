// The gas family renewed in the current configuration (peridynamics/gas_pass.hpp,
// build_renewed_gas_family; peridynamics.gas_refamily_steps): on a sheared, non-uniformly
// expanded cloud of gas beside a solid wall, against brute force. The renewal must be invisible to
// the state (every gas point's density measure gives its X back, so the pressure and the gas
// energy are continuous), keep Newton's third law (each pair in both rows, forces summing to zero),
// and hold exactly the pairs the rule names: two gas points within delta min(s_p, s_q), s = X^(1/d)
// (capped at 2.5), a gas point and a solid within delta; with a coarser gas lattice (a body's
// point_spacing, scale a) s = a X^(1/d) and a gas point reaches solids within a delta.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "peridynamics/gas_pass.hpp"

namespace ballista::test_gas_renewal {
namespace {

/// The checks of the renewal on the sheared cloud; `coarse`: a third of the gas points (every
/// third in storage order) on a lattice twice as coarse (scale 2), the rest scale 1.
void check_renewal(bool coarse) {
  for (int dim : {2, 3}) {
    // A lattice of spacing 1 (gas for z-free coordinate i < 8, a solid wall beyond), sheared
    // (x += 0.8 y: the products sliding past the case) and jittered, then given densities
    // X in [0.7, 20] (compressed to expanded beyond the horizon's growth cap 2.5^d).
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.2, 0.2), ux(0.0, 1.0);
    std::vector<Vec3> x;
    std::vector<std::uint8_t> gas, skip;
    std::vector<double> X, vol0;
    const int nz = dim == 3 ? 6 : 1;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 11; ++i) {
          Vec3 p{{i + 0.8 * j + u(rng), j + u(rng), dim == 3 ? k + u(rng) : 0.0}};
          x.push_back(p);
          const bool g = i < 8;
          gas.push_back(g ? 1 : 0);
          X.push_back(g ? 0.7 + 19.3 * ux(rng) * ux(rng) : 1.0);
          skip.push_back(g && ux(rng) < 0.05 ? 1 : 0);  // a few vented points
          vol0.push_back(1.0);
        }
    const Index n = static_cast<Index>(x.size());
    const double delta = 3.0;
    std::vector<double> scale(static_cast<size_t>(n), 1.0);
    if (coarse)
      for (Index p = 0; p < n; ++p)
        if (gas[p] && p % 3 == 0) scale[p] = 2.0;
    const pd::RenewedGasFamily r = pd::build_renewed_gas_family(x.data(), n, gas.data(), skip.data(), X.data(), delta,
                                                                dim, coarse ? scale.data() : nullptr);
    const pd::BondFamily& f = r.family;
    ASSERT_EQ(f.points(), n);
    ASSERT_EQ(r.length_other.size(), f.other.size());
    ASSERT_EQ(r.weight_other.size(), f.other.size());

    // The pairs: exactly those of the rule, found by brute force, each in both rows.
    auto s_of = [&](Index p) { return gas[p] ? scale[p] * std::clamp(std::pow(X[p], 1.0 / dim), 1.0, 2.5) : 1.0; };
    std::set<std::pair<Index, Index>> expected, listed;
    for (Index p = 0; p < n; ++p)
      for (Index q = 0; q < n; ++q) {
        if (p == q || !(gas[p] || gas[q]) || (gas[p] && skip[p]) || (gas[q] && skip[q])) continue;
        // Between two gas points the smaller horizon; a gas-solid pair the gas end's lattice horizon.
        const double R = gas[p] && gas[q] ? delta * std::min(s_of(p), s_of(q)) : delta * (gas[p] ? scale[p] : scale[q]);
        Vec3 y = x[q] - x[p];
        if (dim == 2) y[2] = 0.0;
        if (dot(y, y) <= R * R) expected.insert({p, q});
      }
    for (Index p = 0; p < n; ++p)
      for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) listed.insert({p, f.other[k]});
    EXPECT_EQ(listed, expected) << dim;
    EXPECT_GT(expected.size(), static_cast<size_t>(20 * n)) << "a family worth the name";

    // Continuity: X back for every gas point in a family, to round-off (12 digits).
    std::vector<double> V(static_cast<size_t>(n), 0.0), g(static_cast<size_t>(n), 0.0);
    for (Index p = 0; p < n; ++p) {
      for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) V[p] += f.volume_factor[k] * vol0[f.other[k]];
      g[p] = gas[p] && !skip[p] ? 1.0e9 * (1.0 + 0.01 * p) : 0.0;  // arbitrary, different pushes
    }
    pd::GasPassArgs a{x.data(), vol0.data(), &f, gas.data(), V.data(), g.data(), dim, r.length_other.data(),
                      r.weight_other.data()};
    double worst = 0.0, fmax = 0.0;
    Vec3 total;
    for (Index p = 0; p < n; ++p) {
      if (gas[p] && !skip[p] && f.offset[p + 1] > f.offset[p])
        worst = std::max(worst, std::abs(pd::density_measure(a, p) / X[p] - 1.0));
      const Vec3 fp = pd::gas_force(a, p);
      total += fp;
      fmax = std::max(fmax, norm(fp));
    }
    EXPECT_LT(worst, 1e-12) << dim;
    // Newton's third law: each bond's two ends add the same two terms (in the opposite order:
    // round-off of one addition per bond).
    EXPECT_LT(norm(total), 1e-13 * fmax * static_cast<double>(n)) << dim;
    EXPECT_GT(fmax, 0.0);
  }
}

TEST(GasRenewal, MeasureContinuousForcesBalancedPairsByTheRule) { check_renewal(false); }

// A coarser gas lattice (bodies[].point_spacing): the same guarantees, the horizon and the reach
// to the solids scaled per gas point.
TEST(GasRenewal, CoarseGasLatticeScalesItsHorizon) { check_renewal(true); }

}  // namespace
}  // namespace ballista::test_gas_renewal
