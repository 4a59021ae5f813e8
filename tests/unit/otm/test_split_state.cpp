// The state of a split point's children (src/otm/split_state.hpp) against exact statements:
//  - a linear field is reproduced exactly at the children (the least-squares gradient of a linear
//    field is its gradient) and its share-weighted sum is the parent's;
//  - the limiter makes no new extrema;
//  - F stays the parent's (each child's cell is half of the parent's, which F maps);
//  - copy and fields left out are unchanged.
// Round-off: LSQ solves over ~50 neighbours of O(1) quantities, ~1e-15 each; bounds 1e-12.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "otm/otm_adaptivity.hpp"
#include "otm/split_state.hpp"

namespace ballista::test_split_state {
namespace {

constexpr double kS0 = 1e-3;

// A lattice of n^dim points at spacing s0 around the origin; the centre point (index `centre`)
// has its cell stretched to 2.5 s0 along x, so it alone splits (along x, children +-0.625 s0 away).
struct Lattice {
  FieldStore f;
  Index centre = 0;
};

Lattice lattice(int dim, int n) {
  Lattice L;
  FieldStore& f = L.f;
  for (const char* v : {"x", "x0", "half_size"}) f.add_real(v, 3, "m");
  for (const char* t : {"F", "R", "stress", otm::kExtentField}) f.add_real(t, 9, "1");
  for (const char* s : {"mass", "volume", "volume0", "eqps", "failed", "substeps"}) f.add_real(s, 1, "1");
  for (const char* i : {"id", "body", "material"}) f.add_int(i, 1, "1");
  const int nz = dim == 3 ? n : 1;
  f.resize(static_cast<Index>(n) * n * nz);
  Index p = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++p) {
        const double h = 0.5 * (n - 1);
        const Vec3 x{{(i - h) * kS0, (j - h) * kS0, dim == 3 ? (k - 0.5 * (nz - 1)) * kS0 : 0.0}};
        if (i == n / 2 && j == n / 2 && (dim == 2 || k == nz / 2)) L.centre = p;
        f.view<Vec3>("x")[p] = x;
        f.view<Vec3>("x0")[p] = x;
        f.view<Vec3>("half_size")[p] = Vec3{{0.5 * kS0, 0.5 * kS0, 0.5 * kS0}};
        f.view<Mat3>("F")[p] = Mat3::identity();
        f.view<Mat3>("R")[p] = Mat3::identity();
        f.view<Mat3>(otm::kExtentField)[p] = Mat3::diag(kS0, kS0, kS0);
        f.real("mass")[p] = 1.0 + 0.01 * static_cast<double>(p % 7);
        f.real("volume0")[p] = kS0 * kS0 * (dim == 3 ? kS0 : 1.0);
        f.real("volume")[p] = f.real("volume0")[p];
        f.ints("id")[p] = p;
      }
  f.view<Mat3>(otm::kExtentField)[L.centre] = Mat3::diag(2.5 * kS0, kS0, kS0);
  return L;
}

// Splits the centre point; returns (a, b) = (the child at +x, the child at -x).
std::pair<Index, Index> split(FieldStore& f, int dim, const otm::SplitStateSpec& spec) {
  const Index n = f.size();
  otm::AdaptivityOptions opt;
  std::int64_t next_id = n;
  const double big = 1.0;
  const std::vector<Index> parents =
      otm::split_points(f, {"mass", "volume0"}, {kS0}, dim, false, Vec3{{-big, -big, -big}}, Vec3{{big, big, big}},
                        opt, spec, "failed", next_id);
  EXPECT_EQ(parents.size(), 1u);
  const Index p = parents.at(0), q = n;
  return f.view<Vec3>("x")[p][0] > f.view<Vec3>("x")[q][0] ? std::make_pair(p, q) : std::make_pair(q, p);
}

const otm::SplitStateSpec kInterpolate{true, {"eqps", "stress"}};

TEST(OtmSplitState, LinearFieldsAreReproducedAndConserved) {
  for (const int dim : {2, 3}) {
    Lattice L = lattice(dim, dim == 2 ? 7 : 5);
    FieldStore& f = L.f;
    auto eqps = [](const Vec3& x) { return 0.1 + 20.0 * x[0] + 5.0 * x[1] - 3.0 * x[2]; };
    auto sxx = [](const Vec3& x) { return 1e8 + 1e10 * x[0] - 2e10 * x[1]; };
    for (Index p = 0; p < f.size(); ++p) {
      const Vec3 x = f.view<Vec3>("x")[p];
      f.real("eqps")[p] = eqps(x);
      f.view<Mat3>("stress")[p] = Mat3::diag(sxx(x), 0.5 * sxx(x), -1e7);
    }
    const Index c = L.centre;
    const double m = f.real("mass")[c];
    const double me = m * f.real("eqps")[c], ms = m * f.view<Mat3>("stress")[c](0, 0);
    const auto [a, b] = split(f, dim, kInterpolate);
    for (const Index k : {a, b}) {
      const Vec3 x = f.view<Vec3>("x")[k];
      EXPECT_NEAR(f.real("eqps")[k], eqps(x), 1e-12) << "dim " << dim;
      EXPECT_NEAR(f.view<Mat3>("stress")[k](0, 0), sxx(x), 1e-12 * 1e8) << "dim " << dim;
      EXPECT_NEAR(f.view<Mat3>("stress")[k](2, 2), -1e7, 1e-12 * 1e7);
    }
    // Share-weighted (mass-weighted) sums are the parent's.
    EXPECT_NEAR(f.real("mass")[a] * f.real("eqps")[a] + f.real("mass")[b] * f.real("eqps")[b], me, 1e-14 * me);
    EXPECT_NEAR(f.real("mass")[a] * f.view<Mat3>("stress")[a](0, 0) + f.real("mass")[b] * f.view<Mat3>("stress")[b](0, 0),
                ms, 1e-14 * ms);
    // The children really differ (0.625 s0 either side, 20 per m: 0.0125 each).
    EXPECT_NEAR(f.real("eqps")[a] - f.real("eqps")[b], 20.0 * 1.25 * kS0, 1e-12);
  }
}

TEST(OtmSplitState, TheLimiterMakesNoNewExtremum) {
  // A step: 0 up to the parent, 1 beyond. The reconstruction would take the -x child below 0;
  // limited, neither child leaves [0, 1] and the mass-weighted sum is still the parent's.
  Lattice L = lattice(2, 7);
  FieldStore& f = L.f;
  const double xc = f.view<Vec3>("x")[L.centre][0];
  for (Index p = 0; p < f.size(); ++p) f.real("eqps")[p] = f.view<Vec3>("x")[p][0] > xc + 1e-9 ? 1.0 : 0.0;
  const auto [a, b] = split(f, 2, kInterpolate);
  for (const Index k : {a, b}) {
    EXPECT_GE(f.real("eqps")[k], 0.0);
    EXPECT_LE(f.real("eqps")[k], 1.0);
  }
  EXPECT_NEAR(f.real("mass")[a] * f.real("eqps")[a] + f.real("mass")[b] * f.real("eqps")[b], 0.0, 1e-15);
}

TEST(OtmSplitState, CopyDiscreteFieldsAndFKeepTheParentsState) {
  auto setup = [](Lattice& L) {
    FieldStore& f = L.f;
    for (Index p = 0; p < f.size(); ++p) {
      const Vec3 x = f.view<Vec3>("x")[p];
      f.real("eqps")[p] = 0.2 + 30.0 * x[0];
      f.real("substeps")[p] = static_cast<double>(p % 3);
      f.view<Mat3>("F")[p] = Mat3::diag(std::exp(50.0 * x[0]), 1.0, 1.0);
    }
  };
  // copy: both children hold the parent's state bit for bit.
  {
    Lattice L = lattice(2, 7);
    setup(L);
    FieldStore& f = L.f;
    const double e = f.real("eqps")[L.centre];
    const Mat3 F = f.view<Mat3>("F")[L.centre];
    const auto [a, b] = split(f, 2, otm::SplitStateSpec{false, {"eqps", "stress"}});
    for (const Index k : {a, b}) {
      EXPECT_EQ(f.real("eqps")[k], e);
      for (int i = 0; i < 9; ++i) EXPECT_EQ(f.view<Mat3>("F")[k].a[i], F.a[i]);
    }
  }
  // A field not named (substeps) and F are copied when interpolating (F varies along x here, so an
  // interpolated F would differ). (A failed point is not split at all: test_otm_adaptivity.cpp.)
  {
    Lattice L = lattice(2, 7);
    setup(L);
    FieldStore& f = L.f;
    const double s = f.real("substeps")[L.centre];
    const Mat3 F = f.view<Mat3>("F")[L.centre];
    const auto [a, b] = split(f, 2, kInterpolate);
    for (const Index k : {a, b})
      for (int i = 0; i < 9; ++i) EXPECT_EQ(f.view<Mat3>("F")[k].a[i], F.a[i]);
    EXPECT_EQ(f.real("substeps")[a], s);
    EXPECT_EQ(f.real("substeps")[b], s);
    EXPECT_NE(f.real("eqps")[a], f.real("eqps")[b]);
  }
}

TEST(OtmSplitState, AnIsolatedPointCopies) {
  // No neighbours within reach (a lone point): no gradient, the state passes on unchanged.
  Lattice L = lattice(2, 1);
  FieldStore& f = L.f;
  f.real("eqps")[0] = 0.7;
  const auto [a, b] = split(f, 2, kInterpolate);
  EXPECT_EQ(f.real("eqps")[a], 0.7);
  EXPECT_EQ(f.real("eqps")[b], 0.7);
}

}  // namespace
}  // namespace ballista::test_split_state
