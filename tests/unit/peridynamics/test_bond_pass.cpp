// The bond pass (peridynamics/bond_pass.hpp), which evaluates a row's intact bonds several at a
// time and falls back to one bond at a time where a group holds a broken, breaking or contacting
// bond, against a plain reference written here from the definitions: every bond seen from both
// ends, f_p = sum over intact bonds of c s beta V_p V_q (x_q - x_p)/|x_q - x_p| (Silling & Askari
// 2005 eq. 20 with the partial-volume factor beta), a bond breaking where s > min(s0_p, s0_q)
// (LAMMPS PERI's rule) exerting no force, and s_max,p = max over intact bonds of -alpha s. The
// cloud is a perturbed lattice with scattered broken bonds and scattered weak points, so that rows
// mix groups the lanes take with groups they hand back, and rows end in a partial group.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "peridynamics/bond_pass.hpp"

namespace test_bond_pass {

using namespace ballista;

namespace {

struct Cloud {
  std::vector<double> x, vol0, s0;
  std::vector<std::int64_t> material;
  std::vector<Index> offset, upper;
  std::vector<std::int32_t> other, mirror;
  std::vector<double> length0, inv_length0;
  std::vector<float> beta;
  std::vector<std::uint8_t> broken;
};

// A 7^3 lattice (spacing 1 mm) with a horizon of 3.015 spacings (up to 122 bonds a point), each
// point moved by up to `jiggle` spacings; 1 in 25 bonds broken beforehand, 1 in 10 points with a
// critical stretch of 0.01 (many of their bonds break), the rest 1.
Cloud make_cloud(double jiggle, unsigned seed) {
  const int n1 = 7;
  const double dx = 1e-3, delta = 3.015 * dx;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Cloud c;
  std::vector<double> x0;
  for (int i = 0; i < n1; ++i)
    for (int j = 0; j < n1; ++j)
      for (int k = 0; k < n1; ++k) {
        x0.insert(x0.end(), {i * dx, j * dx, k * dx});
        c.x.insert(c.x.end(), {(i + jiggle * u(rng)) * dx, (j + jiggle * u(rng)) * dx,
                               (k + jiggle * u(rng)) * dx});
        c.vol0.push_back(dx * dx * dx * (1.0 + 0.1 * u(rng)));
        c.s0.push_back(rng() % 10 == 0 ? 0.01 : 1.0);
        c.material.push_back(0);
      }
  const Index n = static_cast<Index>(c.vol0.size());
  c.offset.push_back(0);
  for (Index p = 0; p < n; ++p) {
    for (Index q = 0; q < n; ++q) {
      if (q == p) continue;
      const double d0 = x0[3 * q] - x0[3 * p], d1 = x0[3 * q + 1] - x0[3 * p + 1],
                   d2 = x0[3 * q + 2] - x0[3 * p + 2];
      const double r0 = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
      if (r0 > delta) continue;
      c.other.push_back(static_cast<std::int32_t>(q));
      c.length0.push_back(r0);
      c.inv_length0.push_back(1.0 / r0);
      c.beta.push_back(r0 > 2.9 * dx ? 0.5f : 1.0f);
    }
    c.offset.push_back(static_cast<Index>(c.other.size()));
    c.upper.push_back(std::upper_bound(c.other.begin() + c.offset[p],
                                       c.other.begin() + c.offset[p + 1],
                                       static_cast<std::int32_t>(p)) -
                      c.other.begin());
  }
  c.mirror.resize(c.other.size());
  for (Index p = 0; p < n; ++p)
    for (Index k = c.offset[p]; k < c.offset[p + 1]; ++k) {
      const Index q = c.other[k];
      const std::int32_t *row = c.other.data() + c.offset[q],
                         *end = c.other.data() + c.offset[q + 1];
      c.mirror[k] =
          static_cast<std::int32_t>(std::find(row, end, static_cast<std::int32_t>(p)) - row);
    }
  c.broken.assign(c.other.size(), 0);
  for (Index p = 0; p < n; ++p)
    for (Index k = c.upper[p]; k < c.offset[p + 1]; ++k)
      if (rng() % 25 == 0) c.broken[k] = c.broken[c.offset[c.other[k]] + c.mirror[k]] = 1;
  return c;
}

struct Sums {
  std::vector<double> f, energy, dis, vb, smax, ec, kc;
  explicit Sums(Index n) : f(3 * n), energy(n), dis(n), vb(n), smax(n, -INFINITY), ec(n), kc(n) {}
};

// Runs the pass over a cloud and checks it against the reference. With `plastic`, every bond
// starts with a plastic stretch in [-0.01, 0.01] and yields at s_y = 0.005 (micro-plastic bonds,
// Silling & Askari 2005): s_p moves by the excess of s - s_p over +-s_y, the force and energy take
// s - s_p, and the plastic work c s_y |ds_p| |xi| beta V_p V_q goes half to each end.
void check_against_reference(bool plastic) {
  for (double jiggle : {0.0, 0.02, 0.2}) {
    Cloud c = make_cloud(jiggle, 7);
    const Index n = static_cast<Index>(c.vol0.size());
    const double cmod = 3e21, alpha = 0.25, sy = 0.005;
    const std::vector<std::uint8_t> broken_before = c.broken;
    std::vector<double> sp;
    if (plastic) {
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> u(-0.01, 0.01);
      sp.assign(c.other.size(), 0.0);
      for (Index p = 0; p < n; ++p)
        for (Index k = c.upper[p]; k < c.offset[p + 1]; ++k)
          sp[k] = sp[c.offset[c.other[k]] + c.mirror[k]] = u(rng);
    }
    const std::vector<double> sp_before = sp;
    Sums s(n);
    pd::BondPassArgs a{c.x.data(),
                       c.vol0.data(),
                       c.material.data(),
                       &cmod,
                       1,
                       c.s0.data(),
                       c.length0.data(),
                       c.inv_length0.data(),
                       c.beta.data(),
                       c.other.data(),
                       c.mirror.data(),
                       c.broken.data(),
                       c.offset.data(),
                       c.upper.data(),
                       plastic ? sp.data() : nullptr,
                       sy,
                       alpha,
                       false,
                       false,
                       0.0,
                       0.0,
                       c.x.data(),
                       s.f.data(),
                       s.energy.data(),
                       s.dis.data(),
                       s.vb.data(),
                       s.smax.data(),
                       s.ec.data(),
                       s.kc.data(),
                       nullptr};
    pd::bond_pass(a, 0, n);

    // The reference: every row in full, each point summing its own bonds.
    Index groups = 0, breaking = 0, flowing = 0;
    for (Index p = 0; p < n; ++p) {
      double f[3] = {0, 0, 0}, tol = 0.0, e = 0.0, etol = 0.0, smx = -INFINITY, vb = 0.0, dis = 0.0,
             dtol = 0.0;
      for (Index k = c.offset[p]; k < c.offset[p + 1]; ++k) {
        const Index q = c.other[k];
        double y[3], rr = 0.0;
        for (int d = 0; d < 3; ++d) {
          y[d] = c.x[3 * q + d] - c.x[3 * p + d];
          rr += y[d] * y[d];
        }
        // The stretch as the pass forms it (r/|xi| - 1 with 1/|xi| stored).
        const double r = std::sqrt(rr), str = r * c.inv_length0[k] - 1.0,
                     vv = c.vol0[p] * c.vol0[q];
        const double cb = cmod * c.length0[k] * c.beta[k] * vv;  // c |xi| beta V_p V_q
        if (broken_before[k]) {
          ASSERT_EQ(c.broken[k], 1);
          vb += c.beta[k] * c.vol0[q];
          if (plastic) {
            EXPECT_EQ(sp[k], sp_before[k]);  // a broken bond no longer flows
          }
          continue;
        }
        double se = str;
        if (plastic) {
          se = str - sp_before[k];
          const double dsp = se > sy ? se - sy : se < -sy ? se + sy : 0.0;
          se -= dsp;
          flowing += dsp != 0.0;
          // Both copies carry the new s_p (to the round-off of the stretch).
          EXPECT_NEAR(sp[k], sp_before[k] + dsp, 1e-15);
          EXPECT_EQ(sp[k], sp[c.offset[q] + c.mirror[k]]);
          dis += 0.5 * cmod * sy * std::abs(dsp) * c.length0[k] * c.beta[k] * vv;
          dtol += 0.5 * cmod * sy * 1e-15 * c.length0[k] * c.beta[k] * vv;
        }
        const bool breaks = str > std::min(c.s0[p], c.s0[q]);
        // Both copies of a bond end up broken exactly when it was broken or breaks now.
        ASSERT_EQ(c.broken[k], breaks) << "bond " << p << "-" << q;
        if (breaks) {
          // The default break rule with x_prev = x: the bond's energy U = c se^2 |xi| beta V V / 2,
          // half to each end, is dissipated.
          vb += c.beta[k] * c.vol0[q];
          ++breaking;
          dis += 0.25 * cb * se * se;
          dtol += 0.25 * cb * (1e-13 * se * se + 2e-15 * std::abs(se) + 1e-30);
          continue;
        }
        const double g = cmod * se * c.beta[k] * vv / r;
        for (int d = 0; d < 3; ++d) {
          f[d] += g * y[d];
          tol += cmod * (1e-13 * std::abs(se) + 1e-15) * c.beta[k] * vv * std::abs(y[d]) / r;
        }
        e += 0.25 * cb * se * se;
        etol += 0.25 * cb * (1e-13 * se * se + 2e-15 * std::abs(se) + 1e-30);
        smx = std::max(smx, -alpha * str);
      }
      // The summation order differs (the reference sums each row in full), and the stretch may
      // differ by its own round-off (the compiler fuses r/|xi| - 1 per context): 1e-13 of each
      // term's magnitude plus what a change of 1e-15 in its stretch makes.
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(s.f[3 * p + d], f[d], tol) << "point " << p;
      EXPECT_NEAR(s.energy[p], e, etol);
      EXPECT_NEAR(s.dis[p], dis, dtol + 1e-13 * dis);
      EXPECT_NEAR(s.vb[p], vb, 1e-13 * vb);
      EXPECT_NEAR(s.smax[p], smx, 1e-15);
      for (Index k = c.upper[p]; k + 8 <= c.offset[p + 1]; k += 8) groups += 1;
    }
    // The cases the test is for actually occur.
    EXPECT_GT(groups, 1000);
    if (jiggle == 0.2) {
      EXPECT_GT(breaking, 100);
    }
    if (plastic && jiggle > 0.0) {
      EXPECT_GT(flowing, 1000);
    }
  }
}

}  // namespace

TEST(BondPass, MatchesEveryBondSeenFromBothEnds) {
  check_against_reference(false);
}

TEST(BondPass, MicroPlasticBondsMatchEveryBondSeenFromBothEnds) {
  check_against_reference(true);
}

}  // namespace test_bond_pass
