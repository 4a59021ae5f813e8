// The contact list's rebuild test (peridynamics/contact_list.hpp) and the chessboard distance of
// the cell bins it uses (points/cell_bins.hpp): the distance's bound against brute force; a gas point far
// from every solid may move by its clearance, one next to them by the skin less the solids'
// motion, and solids by half the skin; and the guarantee behind it: after any motion the test
// accepts, every pair within contact reach is in the list (against a rebuild).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

#include "peridynamics/contact_list.hpp"
#include "points/cell_bins.hpp"

namespace ballista::test_contact_list {
namespace {

TEST(CellBins, ChessboardDistanceBoundsTheNearestPoint) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int dim : {2, 3}) {
    std::vector<Vec3> x;
    for (int k = 0; k < 40; ++k) x.push_back(Vec3{{20.0 * u(rng), 12.0 * u(rng), dim == 3 ? 9.0 * u(rng) : 0.0}});
    const CellBins bins(x.data(), static_cast<Index>(x.size()), 1.0, dim);
    const std::vector<std::uint8_t> d = bins.chessboard_distance(5);
    // Direct check: distance 0 exactly at the occupied bins, and the bound it promises: every
    // point is at least (d - 1) bin sizes from a probe in a bin at distance d.
    for (int k = 0; k < 2000; ++k) {
      const Vec3 y{{20.0 * u(rng), 12.0 * u(rng), dim == 3 ? 9.0 * u(rng) : 0.0}};
      const int dist = d[bins.bin_of(y)];
      double nearest = INFINITY;
      for (const Vec3& p : x) {
        double cheb = 0.0;
        for (int a = 0; a < dim; ++a) cheb = std::max(cheb, std::abs(p[a] - y[a]));
        nearest = std::min(nearest, cheb);
      }
      EXPECT_GE(nearest, (dist - 1) * bins.size() - 1e-12) << "dim " << dim;
      // Tight: the nearest point is within (d + 1) bin sizes (or the cap was reached).
      bool inside = true;  // the upper bound holds inside the points' box (outside, bins clamp)
      for (int a = 0; a < dim; ++a) {
        double lo = INFINITY, hi = -INFINITY;
        for (const Vec3& p : x) lo = std::min(lo, p[a]), hi = std::max(hi, p[a]);
        inside = inside && y[a] >= lo && y[a] <= hi;
      }
      EXPECT_GE(nearest, bins.outside_distance(y) - 1e-12);
      if (dist < 5 && inside) {
        EXPECT_LE(nearest, (dist + 1) * bins.size() + 1e-12) << "dim " << dim;
      }
    }
    for (const Vec3& p : x) EXPECT_EQ(d[bins.bin_of(p)], 0);
  }
}

// A column of solid points along z and a cloud of gas points around it out to 20 dx.
struct GasAroundColumn {
  std::vector<Vec3> x, x0;
  std::vector<std::int64_t> body;
  std::vector<std::uint8_t> gas;
};

GasAroundColumn column_in_gas(double dx) {
  GasAroundColumn s;
  for (int k = 0; k < 20; ++k) {
    s.x.push_back(Vec3{{0.0, 0.0, k * dx}});
    s.body.push_back(0);
    s.gas.push_back(0);
  }
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 400; ++k) {
    s.x.push_back(Vec3{{20 * dx * u(rng), 20 * dx * u(rng), 10 * dx + 10 * dx * u(rng)}});
    s.body.push_back(1);
    s.gas.push_back(1);
  }
  s.x0 = s.x;
  return s;
}

// Every never-bonded solid-gas or solid-solid pair within reach (1.35 dx) of each other at x.
std::set<std::pair<Index, Index>> within_reach(const GasAroundColumn& s, const std::vector<Vec3>& x, double dx) {
  std::set<std::pair<Index, Index>> out;
  const Index n = static_cast<Index>(x.size());
  for (Index p = 0; p < n; ++p)
    for (Index q = p + 1; q < n; ++q) {
      if (s.gas[p] && s.gas[q]) continue;
      if (s.body[p] == s.body[q]) continue;  // one body here is bonded within the horizon (delta large)
      if (norm(x[q] - x[p]) < 1.35 * dx) out.insert({p, q});
    }
  return out;
}

TEST(PdContactList, GasFarFromTheSolidsMovesByItsClearance) {
  const double dx = 1e-3, skin = 0.5 * dx, delta = 100 * dx;
  GasAroundColumn s = column_in_gas(dx);
  const Index n = static_cast<Index>(s.x.size());
  pd::ContactList list;
  pd::build_contact_list(list, s.x.data(), s.x0.data(), s.body.data(), n, delta, dx, skin, 3, nullptr, s.gas.data(),
                         nullptr, true);
  // A far gas point (the farthest from the column) may move several skins; a near one only the skin.
  Index far = -1, near = -1;
  double dfar = 0.0, dnear = INFINITY;
  for (Index p = 0; p < n; ++p) {
    if (!s.gas[p]) continue;
    const double r = std::hypot(s.x[p][0], s.x[p][1]);
    if (r > dfar) dfar = r, far = p;
    if (r < dnear) dnear = r, near = p;
  }
  EXPECT_GT(list.allowance[far], 10 * skin);
  EXPECT_DOUBLE_EQ(list.allowance[near], skin);
  std::vector<Vec3> x = s.x;
  x[far] += Vec3{{0.9 * list.allowance[far], 0.0, 0.0}};
  EXPECT_FALSE(list.stale(x.data(), n, list.solid_moved(x.data(), n, nullptr, s.gas.data()), nullptr, s.gas.data()));
  x[far] += Vec3{{0.2 * list.allowance[far], 0.0, 0.0}};
  EXPECT_TRUE(list.stale(x.data(), n, list.solid_moved(x.data(), n, nullptr, s.gas.data()), nullptr, s.gas.data()));
  // The near gas point: 0.9 skin alone is fine, with the column moved by 0.2 skin it is not; the
  // column alone rebuilds past skin/2.
  x = s.x;
  x[near] += Vec3{{0.9 * skin, 0.0, 0.0}};
  EXPECT_FALSE(list.stale(x.data(), n, list.solid_moved(x.data(), n, nullptr, s.gas.data()), nullptr, s.gas.data()));
  for (Index p = 0; p < 20; ++p) x[p] += Vec3{{0.0, 0.2 * skin, 0.0}};
  EXPECT_TRUE(list.stale(x.data(), n, list.solid_moved(x.data(), n, nullptr, s.gas.data()), nullptr, s.gas.data()));
  x = s.x;
  for (Index p = 0; p < 20; ++p) x[p] += Vec3{{0.0, 0.51 * skin, 0.0}};
  EXPECT_TRUE(list.stale(x.data(), n, list.solid_moved(x.data(), n, nullptr, s.gas.data()), nullptr, s.gas.data()));
  // Without gas flags it is the classic test: any point past skin/2.
  x = s.x;
  x[far] += Vec3{{0.51 * skin, 0.0, 0.0}};
  pd::ContactList plain;
  pd::build_contact_list(plain, s.x.data(), s.x0.data(), s.body.data(), n, delta, dx, skin, 3);
  EXPECT_TRUE(plain.stale(x.data(), n, plain.solid_moved(x.data(), n)));
}

// The guarantee: random motions of gas and solids, the list rebuilt only when the test says so;
// after every move every pair within reach is in the list.
TEST(PdContactList, NoPairComesWithinReachUnseen) {
  const double dx = 1e-3, skin = 0.5 * dx, delta = 100 * dx;
  GasAroundColumn s = column_in_gas(dx);
  const Index n = static_cast<Index>(s.x.size());
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> x = s.x, vel(static_cast<size_t>(n));
  for (Index p = 0; p < n; ++p)  // gas converging on the column at up to 0.3 dx per move, solids 0.05 dx
    vel[p] = s.gas[p] ? Vec3{{-0.3 * dx * x[p][0] / (20 * dx) + 0.02 * dx * u(rng), -0.3 * dx * x[p][1] / (20 * dx), 0.0}}
                      : Vec3{{0.05 * dx * u(rng), 0.05 * dx * u(rng), 0.0}};
  pd::ContactList list;
  pd::build_contact_list(list, x.data(), s.x0.data(), s.body.data(), n, delta, dx, skin, 3, nullptr, s.gas.data(),
                         nullptr, true);
  int builds = 1, pairs_seen = 0;
  for (int step = 0; step < 60; ++step) {
    for (Index p = 0; p < n; ++p) x[p] += vel[p];
    if (list.stale(x.data(), n, list.solid_moved(x.data(), n, nullptr, s.gas.data()), nullptr, s.gas.data())) {
      pd::build_contact_list(list, x.data(), s.x0.data(), s.body.data(), n, delta, dx, skin, 3, nullptr,
                             s.gas.data(), nullptr, true);
      ++builds;
    }
    for (const auto& [p, q] : within_reach(s, x, dx)) {
      ++pairs_seen;
      const auto* row = list.other.data();
      const bool found = std::find(row + list.offset[p], row + list.offset[p + 1], static_cast<std::int32_t>(q)) !=
                         row + list.offset[p + 1];
      ASSERT_TRUE(found) << "step " << step << ": pair " << p << "-" << q << " within reach but not listed";
    }
  }
  EXPECT_GT(pairs_seen, 50);  // the gas did reach the column
  EXPECT_LT(builds, 50);      // and the list was not rebuilt every move
  std::printf("contact list: %d builds in 60 moves, %d pair-moves within reach\n", builds, pairs_seen);
}

// Gas on a coarser lattice (bodies[].point_spacing, scale a): a gas-solid pair reaches
// 1.35 dx (a + 1)/2, the sum of the two half-cells, and the list holds exactly the pairs within
// that plus the skin, with that reach (the column's points are 1 dx apart; gas at scale 2 reaches
// 2.03 dx instead of 1.35 dx). The rebuild guarantee holds with the wider reach.
TEST(PdContactList, CoarseGasReachesTheSumOfTheHalfCells) {
  const double dx = 1e-3, skin = 0.5 * dx, delta = 100 * dx;
  GasAroundColumn s = column_in_gas(dx);
  const Index n = static_cast<Index>(s.x.size());
  std::vector<double> scale(static_cast<size_t>(n), 1.0);
  for (Index p = 0; p < n; ++p)
    if (s.gas[p]) scale[p] = 2.0;
  pd::ContactList list;
  pd::build_contact_list(list, s.x.data(), s.x0.data(), s.body.data(), n, delta, dx, skin, 3, nullptr, s.gas.data(),
                         nullptr, true, scale.data());
  std::set<std::pair<Index, Index>> expected, listed;
  for (Index p = 0; p < n; ++p)
    for (Index q = 0; q < n; ++q) {
      if (p == q || (s.gas[p] && s.gas[q]) || s.body[p] == s.body[q]) continue;
      if (norm(s.x[q] - s.x[p]) <= 1.35 * dx * 0.5 * (scale[p] + scale[q]) + skin) expected.insert({p, q});
    }
  for (Index p = 0; p < n; ++p)
    for (Index k = list.offset[p]; k < list.offset[p + 1]; ++k) {
      const Index q = list.other[k];
      listed.insert({p, q});
      const double r0 = norm(s.x0[q] - s.x0[p]);
      EXPECT_DOUBLE_EQ(list.reach[k], std::min(0.9 * r0, 1.35 * dx * 0.5 * (scale[p] + scale[q])));
    }
  EXPECT_EQ(listed, expected);
  EXPECT_GT(expected.size(), within_reach(s, s.x, dx).size());  // more pairs than at scale 1
  // Gas converging on the column: every pair within the wider reach stays listed between rebuilds.
  std::vector<Vec3> x = s.x;
  int builds = 1;
  for (int step = 0; step < 40; ++step) {
    for (Index p = 0; p < n; ++p)
      if (s.gas[p]) x[p] += Vec3{{-0.3 * dx * x[p][0] / (20 * dx), -0.3 * dx * x[p][1] / (20 * dx), 0.0}};
    if (list.stale(x.data(), n, list.solid_moved(x.data(), n, nullptr, s.gas.data()), nullptr, s.gas.data())) {
      pd::build_contact_list(list, x.data(), s.x0.data(), s.body.data(), n, delta, dx, skin, 3, nullptr, s.gas.data(),
                             nullptr, true, scale.data());
      ++builds;
    }
    for (Index p = 0; p < n; ++p)
      for (Index q = 0; q < n; ++q) {
        if (p == q || (s.gas[p] && s.gas[q]) || s.body[p] == s.body[q]) continue;
        if (norm(x[q] - x[p]) >= 1.35 * dx * 0.5 * (scale[p] + scale[q])) continue;
        const auto* row = list.other.data();
        ASSERT_NE(std::find(row + list.offset[p], row + list.offset[p + 1], static_cast<std::int32_t>(q)),
                  row + list.offset[p + 1])
            << "step " << step << ": pair " << p << "-" << q << " within reach but not listed";
      }
  }
  EXPECT_LT(builds, 40);
}

// The test on relative motion (ContactList::stale_relative): random motions of gas and solids
// on top of a uniform expansion of everything about the column's axis and a drift of everything
// along x (a case flying and expanding as a whole), the list rebuilt only when the classic test
// and the relative one both say so; after every move every pair within reach is listed. With the
// gas converging on the column pairs keep coming within reach; without, the drift alone moves
// every point past half the skin each move, so the classic test rebuilds far more often.
TEST(PdContactList, RelativeMotionTestMissesNoPair) {
  const double dx = 1e-3, skin = 0.5 * dx, delta = 100 * dx;
  GasAroundColumn s = column_in_gas(dx);
  const Index n = static_cast<Index>(s.x.size());
  auto run = [&](bool relative, double converge) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec3> vel(static_cast<size_t>(n));
    for (Index p = 0; p < n; ++p)
      vel[p] = s.gas[p] ? Vec3{{-converge * dx * s.x[p][0] / (20 * dx) + 0.02 * dx * u(rng),
                                -converge * dx * s.x[p][1] / (20 * dx), 0.01 * dx * u(rng)}}
                        : Vec3{{0.02 * dx * u(rng), 0.02 * dx * u(rng), 0.0}};
    std::vector<Vec3> x = s.x;
    pd::ContactList list;
    pd::build_contact_list(list, x.data(), s.x0.data(), s.body.data(), n, delta, dx, skin, 3, nullptr, s.gas.data(),
                           nullptr, true);
    int builds = 1, seen = 0;
    for (int step = 0; step < 60; ++step) {
      for (Index p = 0; p < n; ++p) {
        x[p] += vel[p];
        x[p] += Vec3{{0.3 * dx + 0.01 * x[p][0], 0.01 * x[p][1], 0.0}};  // drift, 1 % expansion per move
      }
      bool stale = list.stale(x.data(), n, list.solid_moved(x.data(), n, nullptr, s.gas.data()), nullptr, s.gas.data());
      if (stale && relative) stale = list.stale_relative(x.data(), n, 3, nullptr, s.gas.data());
      if (stale) {
        pd::build_contact_list(list, x.data(), s.x0.data(), s.body.data(), n, delta, dx, skin, 3, nullptr,
                               s.gas.data(), nullptr, true);
        ++builds;
      }
      for (const auto& [p, q] : within_reach(s, x, dx)) {
        ++seen;
        const auto* row = list.other.data();
        EXPECT_NE(std::find(row + list.offset[p], row + list.offset[p + 1], static_cast<std::int32_t>(q)),
                  row + list.offset[p + 1])
            << (relative ? "relative" : "classic") << " step " << step << ": pair " << p << "-" << q << " unlisted";
      }
    }
    return std::pair<int, int>{builds, seen};
  };
  // Converging gas: pairs keep arriving, none is missed.
  const auto [converging_builds, seen] = run(true, 0.2);
  EXPECT_GT(seen, 50);
  EXPECT_GT(converging_builds, 1);
  // Drifting and expanding together: far fewer builds.
  const int classic = run(false, 0.0).first, relative = run(true, 0.0).first;
  std::printf("contact list drifting and expanding: %d builds with the classic test, %d with the relative one; "
              "%d with converging gas (%d pair-moves within reach)\n",
              classic, relative, converging_builds, seen);
  EXPECT_GT(classic, 30);  // the drift alone passes skin/2 every move
  EXPECT_LT(relative, classic / 3);
  // A pair that does close in: two solids of different bodies approaching head-on by 0.6 skin
  // each is stale; moving both together by the same distance is not.
  std::vector<Vec3> x = {Vec3{{0.0, 0.0, 0.0}}, Vec3{{3.0 * dx, 0.0, 0.0}}};
  const std::vector<Vec3> x0 = x;
  const std::vector<std::int64_t> body = {0, 1};
  pd::ContactList pair;
  pd::build_contact_list(pair, x.data(), x0.data(), body.data(), 2, delta, dx, skin, 3);
  std::vector<Vec3> together = {x[0] + Vec3{{5.0 * skin, 0.0, 0.0}}, x[1] + Vec3{{5.0 * skin, 0.0, 0.0}}};
  EXPECT_FALSE(pair.stale_relative(together.data(), 2, 3));
  std::vector<Vec3> closing = {x[0] + Vec3{{0.6 * skin, 0.0, 0.0}}, x[1] - Vec3{{0.6 * skin, 0.0, 0.0}}};
  EXPECT_TRUE(pair.stale_relative(closing.data(), 2, 3));
}

// The relative test in 2D and 3D with coarse gas (scale 2: reach 2.03 dx) and gas vented on the
// way (skipped, as the solver does): a wall of solids and a cloud of gas crossing it at random,
// everything drifting and expanding; after every move every unvented pair within its reach is
// listed.
TEST(PdContactList, RelativeTestWithCoarseAndVentedGasIn2DAnd3D) {
  const double dx = 1e-3, skin = 0.5 * dx, delta = 100 * dx;
  for (int dim : {2, 3}) {
    std::mt19937 rng(31 + dim);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec3> x;
    std::vector<std::int64_t> body;
    std::vector<std::uint8_t> gas;
    std::vector<double> scale;
    const int nz = dim == 3 ? 6 : 1;
    for (int k = 0; k < nz; ++k)  // a wall of solids at x = 0, one body
      for (int j = 0; j < 12; ++j) {
        x.push_back(Vec3{{0.0, j * dx, dim == 3 ? k * dx : 0.0}});
        body.push_back(0), gas.push_back(0), scale.push_back(1.0);
      }
    for (int k = 0; k < 150; ++k) {  // gas on both sides
      x.push_back(Vec3{{8 * dx * u(rng), 6 * dx + 8 * dx * u(rng), dim == 3 ? 3 * dx + 4 * dx * u(rng) : 0.0}});
      body.push_back(1), gas.push_back(1), scale.push_back(2.0);
    }
    const Index n = static_cast<Index>(x.size());
    const std::vector<Vec3> x0 = x;
    std::vector<Vec3> vel(static_cast<size_t>(n));
    for (Index p = 0; p < n; ++p)
      vel[p] = gas[p] ? Vec3{{-0.15 * dx * x[p][0] / (8 * dx) + 0.05 * dx * u(rng), 0.05 * dx * u(rng),
                              dim == 3 ? 0.05 * dx * u(rng) : 0.0}}
                      : Vec3{{0.01 * dx * u(rng), 0.01 * dx * u(rng), 0.0}};
    std::vector<std::uint8_t> vented(static_cast<size_t>(n), 0);
    pd::ContactList list;
    auto build = [&] {
      pd::build_contact_list(list, x.data(), x0.data(), body.data(), n, delta, dx, skin, dim, vented.data(), gas.data(),
                             nullptr, true, scale.data());
    };
    build();
    int builds = 1, seen = 0;
    for (int step = 0; step < 80; ++step) {
      for (Index p = 0; p < n; ++p) {
        x[p] += vel[p];
        x[p] += Vec3{{0.2 * dx + 0.005 * x[p][0], 0.005 * x[p][1], 0.0}};
      }
      if (step % 10 == 5)  // a few gas points leave the run
        for (Index p = 0; p < n; ++p)
          if (gas[p] && !vented[p] && u(rng) > 0.9) vented[p] = 1;
      // The solver's rule: the classic test, then the relative one (vented points skipped).
      if (list.stale(x.data(), n, list.solid_moved(x.data(), n, vented.data(), gas.data()), vented.data(), gas.data()) &&
          list.stale_relative(x.data(), n, dim, vented.data(), gas.data())) {
        build();
        ++builds;
      }
      for (Index p = 0; p < n; ++p)
        for (Index q = 0; q < n; ++q) {
          if (p == q || vented[p] || vented[q] || (gas[p] && gas[q]) || body[p] == body[q]) continue;
          Vec3 d = x[q] - x[p];
          if (dim == 2) d[2] = 0.0;
          if (norm(d) >= 1.35 * dx * 0.5 * (scale[p] + scale[q])) continue;
          ++seen;
          const auto* row = list.other.data();
          ASSERT_NE(std::find(row + list.offset[p], row + list.offset[p + 1], static_cast<std::int32_t>(q)),
                    row + list.offset[p + 1])
              << "dim " << dim << " step " << step << ": pair " << p << "-" << q << " within reach but not listed";
        }
    }
    EXPECT_GT(seen, 50) << dim;       // the gas did reach the wall
    EXPECT_LT(builds, 60) << dim;     // the drift (0.2 dx a move) alone would rebuild every other move
    std::printf("relative test, %dD, coarse and vented gas: %d builds in 80 moves, %d pair-moves within reach\n",
                dim, builds, seen);
  }
}

}  // namespace
}  // namespace ballista::test_contact_list

namespace ballista::test_contact_list {
namespace {

// The rows against a search from every point, by brute force: each pair is searched for once (a
// solid pair from its lower end, a gas-solid pair from its gas end) and given to both rows, so each
// row must be exactly the never-bonded points within reach + skin (gas-gas aside), in increasing
// index (or key), with the pair's reach min(0.9 |xi|, reach) the same in both rows to the bit. Three bodies of solids (two lattices that interpenetrate
// and a scattered one, bonded within delta inside each body) and gas, in 2D and 3D, with and
// without a key.
TEST(PdContactList, RowsAreTheSearchFromEveryPoint) {
  const double dx = 1e-3, skin = 0.5 * dx, delta = 3.0 * dx, range = 1.35 * dx;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int dim : {2, 3})
    for (bool with_key : {false, true}) {
      std::vector<Vec3> x, x0;
      std::vector<std::int64_t> body, key;
      std::vector<std::uint8_t> gas;
      auto add = [&](const Vec3& ref, const Vec3& now, std::int64_t b, bool g) {
        x0.push_back(ref);
        x.push_back(now);
        body.push_back(b);
        gas.push_back(g ? 1 : 0);
      };
      const int nz = dim == 3 ? 6 : 1;
      for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j)
          for (int k = 0; k < nz; ++k) {
            const Vec3 a{{i * dx, j * dx, k * dx}};
            // Body 0 stretched and sheared so that points once beyond delta come near each other.
            add(a, Vec3{{0.55 * a[0] + 0.3 * a[1], 1.4 * a[1], a[2]}} + 0.2 * dx * Vec3{{u(rng), u(rng), 0.0}}, 0,
                false);
            add(a + Vec3{{0.5 * dx, 0.5 * dx, 0.0}}, a + Vec3{{0.5 * dx, 0.5 * dx, 0.0}}, 1, false);
          }
      for (int k = 0; k < 150; ++k) {
        const Vec3 p{{12 * dx * 0.5 * (u(rng) + 1), 12 * dx * 0.5 * (u(rng) + 1), dim == 3 ? 3 * dx * u(rng) : 0.0}};
        add(p, p + 0.5 * dx * Vec3{{u(rng), u(rng), dim == 3 ? u(rng) : 0.0}}, 2, false);
        add(p, p + Vec3{{0.3 * dx, 0.0, 0.0}}, 3, true);
      }
      const Index n = static_cast<Index>(x.size());
      for (Index p = 0; p < n; ++p) key.push_back((p * 7919) % n);  // a permutation: n is not a multiple of 7919
      pd::ContactList list;
      pd::build_contact_list(list, x.data(), x0.data(), body.data(), n, delta, dx, skin, dim, nullptr, gas.data(),
                             with_key ? key.data() : nullptr);
      long pairs = 0;
      for (Index p = 0; p < n; ++p) {
        std::vector<std::pair<Index, double>> want;
        for (Index q = 0; q < n; ++q) {
          if (q == p || (gas[p] && gas[q])) continue;
          Vec3 d = x[q] - x[p], d0 = x0[q] - x0[p];
          if (dim == 2) d[2] = d0[2] = 0.0;
          const double cut = range + skin, r02 = dot(d0, d0);
          if (dot(d, d) > cut * cut) continue;
          if (body[q] == body[p] && r02 <= delta * delta * (1.0 + 2e-9)) continue;
          want.push_back({q, std::min(0.9 * std::sqrt(r02), range)});
        }
        std::sort(want.begin(), want.end(), [&](const auto& a, const auto& b) {
          return with_key ? key[a.first] < key[b.first] : a.first < b.first;
        });
        ASSERT_EQ(list.offset[p + 1] - list.offset[p], static_cast<Index>(want.size())) << "dim " << dim << " p " << p;
        for (size_t j = 0; j < want.size(); ++j) {
          const Index k = list.offset[p] + static_cast<Index>(j);
          ASSERT_EQ(list.other[k], want[j].first) << "dim " << dim << " p " << p;
          // Brute force's arithmetic may round differently (FMA contraction where dot() is
          // inlined): 1e-14 of the reach. The two rows' copies of a pair must agree exactly.
          ASSERT_NEAR(list.reach[k], want[j].second, 1e-14 * range) << "dim " << dim << " p " << p;
          const Index q = want[j].first;
          const auto* back = std::find(list.other.data() + list.offset[q], list.other.data() + list.offset[q + 1],
                                       static_cast<std::int32_t>(p));
          ASSERT_NE(back, list.other.data() + list.offset[q + 1]) << "dim " << dim << " p " << p << " q " << q;
          ASSERT_EQ(list.reach[back - list.other.data()], list.reach[k]) << "dim " << dim << " p " << p;
        }
        pairs += static_cast<long>(want.size());
      }
      EXPECT_GT(pairs, 200) << "dim " << dim;  // the check saw solid-solid, gas-solid and cross-body pairs
    }
}

}  // namespace
}  // namespace ballista::test_contact_list
