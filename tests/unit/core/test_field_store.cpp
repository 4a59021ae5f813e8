// FieldStore: every operation that moves points (permute, compact, append_from, resize) must move
// every field of a point together. Each point's values encode its original index, so any field
// that lags behind, is shifted by a component or is filled with the wrong default is detected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "core/field_store.hpp"
#include "core/tensor.hpp"

namespace test_field_store {

using namespace ballista;

namespace {

// Fields of several shapes and both types, declared in an order that interleaves them.
void declare(FieldStore& s) {
  s.add_int("id", 1, "1");
  s.add_real("scalar", 1, "m");
  s.add_real("vec", 3, "m/s");
  s.add_int("pair", 2, "1");
  s.add_real("tensor", 9, "Pa", false);
  s.add_real("seven", 1, "1", true, 7.0);  // non-zero default
  s.add_int("minus_one", 1, "1", true, -1);
}

// Value of field component c of the point whose tag is t (all distinct across fields/components).
double rv(int field, std::int64_t t, int c) { return 1e6 * field + 100.0 * static_cast<double>(t) + c + 0.25; }
std::int64_t iv(int field, std::int64_t t, int c) { return 1000000 * field + 100 * t + c; }

void fill(FieldStore& s, Index first, Index last, std::int64_t tag0) {
  auto* id = s.ints("id");
  auto* sc = s.real("scalar");
  auto* v = s.view<Vec3>("vec");
  auto* pair = s.ints("pair");
  auto* T = s.view<Mat3>("tensor");
  for (Index p = first; p < last; ++p) {
    const std::int64_t t = tag0 + (p - first);
    id[p] = t;
    sc[p] = rv(1, t, 0);
    for (int c = 0; c < 3; ++c) v[p][c] = rv(2, t, c);
    for (int c = 0; c < 2; ++c) pair[2 * p + c] = iv(3, t, c);
    for (int c = 0; c < 9; ++c) T[p].a[c] = rv(4, t, c);
  }
}

// Point p holds exactly the values of tag t in every field (defaults untouched).
void expect_point(const FieldStore& s, Index p, std::int64_t t) {
  const auto* id = s.ints("id");
  const auto* sc = s.real("scalar");
  const auto* v = s.view<Vec3>("vec");
  const auto* pair = s.ints("pair");
  const auto* T = s.view<Mat3>("tensor");
  ASSERT_EQ(id[p], t) << "point " << p;
  EXPECT_EQ(sc[p], rv(1, t, 0)) << "point " << p;
  for (int c = 0; c < 3; ++c) EXPECT_EQ(v[p][c], rv(2, t, c)) << "point " << p << " comp " << c;
  for (int c = 0; c < 2; ++c) EXPECT_EQ(pair[2 * p + c], iv(3, t, c)) << "point " << p;
  for (int c = 0; c < 9; ++c) EXPECT_EQ(T[p].a[c], rv(4, t, c)) << "point " << p << " comp " << c;
  EXPECT_EQ(s.real("seven")[p], 7.0);
  EXPECT_EQ(s.ints("minus_one")[p], -1);
}

}  // namespace

TEST(FieldStore, ResizeFillsDeclaredDefaultsAndKeepsValues) {
  FieldStore s;
  declare(s);
  s.resize(5);
  fill(s, 0, 5, 0);
  s.resize(12);
  for (Index p = 0; p < 5; ++p) expect_point(s, p, p);
  for (Index p = 5; p < 12; ++p) {
    EXPECT_EQ(s.real("seven")[p], 7.0);
    EXPECT_EQ(s.ints("minus_one")[p], -1);
    EXPECT_EQ(s.real("scalar")[p], 0.0);
    EXPECT_EQ(s.view<Mat3>("tensor")[p].a[8], 0.0);
  }
  // A field declared after points exist is sized and filled with its default.
  s.add_real("late", 3, "m", true, 2.5);
  for (Index p = 0; p < 12; ++p)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(s.view<Vec3>("late")[p][c], 2.5);
  s.resize(3);
  EXPECT_EQ(s.size(), 3);
  for (Index p = 0; p < 3; ++p) expect_point(s, p, p);
}

TEST(FieldStore, DeclarationsAreIdempotentAndShapeChecked) {
  FieldStore s;
  declare(s);
  const size_t n = s.fields().size();
  s.add_real("vec", 3, "m/s");  // same shape: no-op
  s.add_int("id", 1, "1");
  EXPECT_EQ(s.fields().size(), n);
  EXPECT_THROW(s.add_real("vec", 1, "m/s"), Error);
  EXPECT_THROW(s.add_int("scalar", 1, "1"), Error);  // same name, other type
  EXPECT_THROW(s.view<Vec3>("scalar"), Error);       // wrong component count
  EXPECT_THROW(s.view<Mat3>("vec"), Error);
  EXPECT_THROW(s.real("id"), Error);  // int field through the real accessor
  EXPECT_THROW(s.ints("scalar"), Error);
  EXPECT_THROW(s.real("nope"), Error);
  EXPECT_THROW((void)s.info("nope"), Error);
  EXPECT_EQ(s.info("tensor").ncomp, 9);
  EXPECT_FALSE(s.info("tensor").output);
  EXPECT_EQ(s.info("vec").unit, "m/s");
}

TEST(FieldStore, PermuteMovesEveryFieldTogether) {
  // Above kParallelThreshold so that the parallel path of the copy is exercised too.
  for (Index n : {Index(17), Index(3 * kParallelThreshold + 11)}) {
    FieldStore s;
    declare(s);
    s.resize(n);
    fill(s, 0, n, 0);
    std::vector<Index> order(n);
    std::iota(order.begin(), order.end(), Index(0));
    std::mt19937_64 rng(42 + n);
    std::shuffle(order.begin(), order.end(), rng);
    s.permute(order);
    ASSERT_EQ(s.size(), n);
    for (Index i = 0; i < n; ++i) expect_point(s, i, order[i]);
    EXPECT_THROW(s.permute(std::vector<Index>(n - 1, 0)), Error);
  }
}

TEST(FieldStore, CompactKeepsSelectedPointsInOrder) {
  const Index n = 101;
  FieldStore s;
  declare(s);
  s.resize(n);
  fill(s, 0, n, 0);
  std::vector<char> keep(n);
  std::mt19937 rng(7);
  std::vector<std::int64_t> expected;
  for (Index p = 0; p < n; ++p) {
    keep[p] = (rng() % 3) != 0;
    if (keep[p]) expected.push_back(p);
  }
  s.compact(keep);
  ASSERT_EQ(s.size(), static_cast<Index>(expected.size()));
  for (Index i = 0; i < s.size(); ++i) expect_point(s, i, expected[i]);
  // Growing again after a compact gives defaults, not stale values of removed points.
  s.resize(s.size() + 4);
  for (Index i = s.size() - 4; i < s.size(); ++i) {
    EXPECT_EQ(s.real("scalar")[i], 0.0);
    EXPECT_EQ(s.ints("minus_one")[i], -1);
  }
  EXPECT_THROW(s.compact(std::vector<char>(3, 1)), Error);
  // Removing everything.
  s.compact(std::vector<char>(s.size(), 0));
  EXPECT_EQ(s.size(), 0);
}

TEST(FieldStore, AppendFromCopiesSelectedPointsOfEveryField) {
  FieldStore a;
  declare(a);
  a.resize(6);
  fill(a, 0, 6, 0);
  FieldStore b = a.empty_like();
  EXPECT_EQ(b.size(), 0);
  ASSERT_EQ(b.fields().size(), a.fields().size());
  b.resize(9);
  fill(b, 0, 9, 500);
  const std::vector<Index> which = {8, 0, 4, 4};
  a.append_from(b, which);
  ASSERT_EQ(a.size(), 10);
  for (Index p = 0; p < 6; ++p) expect_point(a, p, p);
  for (size_t q = 0; q < which.size(); ++q) expect_point(a, 6 + q, 500 + which[q]);
  // b is untouched.
  for (Index p = 0; p < 9; ++p) expect_point(b, p, 500 + p);

  // Layouts that differ are refused.
  FieldStore c;
  c.add_int("id", 1, "1");
  c.resize(1);
  EXPECT_THROW(a.append_from(c, {0}), Error);
  FieldStore d;
  d.add_int("id", 1, "1");
  d.add_real("scalar", 3, "m");  // same count, different shape
  d.add_real("vec", 3, "m/s");
  d.add_int("pair", 2, "1");
  d.add_real("tensor", 9, "Pa");
  d.add_real("seven", 1, "1");
  d.add_int("minus_one", 1, "1");
  d.resize(1);
  EXPECT_THROW(a.append_from(d, {0}), Error);
  // Same names and shapes but a different type: refused too (would read the wrong array).
  FieldStore e = a.empty_like();
  FieldStore f;
  for (const auto& fi : a.fields()) {
    const bool flip = fi.name == "seven";
    if ((fi.type == FieldType::Real) != flip) f.add_real(fi.name, fi.ncomp, fi.unit);
    else f.add_int(fi.name, fi.ncomp, fi.unit);
  }
  f.resize(1);
  EXPECT_THROW(e.append_from(f, {0}), Error);
  EXPECT_EQ(e.size(), 0);
  // Indices outside the source are refused.
  EXPECT_THROW(a.append_from(b, {9}), Error);
  // A refused append leaves the store as it was (no half-appended points).
  ASSERT_EQ(a.size(), 10);
  for (Index p = 0; p < 6; ++p) expect_point(a, p, p);
}

// The layout version changes with every operation that can move points or change their number,
// and only with those (caches of point indices, e.g. the pressure loads' surface points, key on it).
TEST(FieldStore, LayoutVersionTracksEveryReorderingAndNothingElse) {
  ballista::FieldStore s;
  s.add_real("x", 3, "m");
  s.resize(4);
  auto v = s.layout_version();
  s.real("x")[0] = 1.0;  // values change, places do not
  s.add_real("y", 1, "m");
  EXPECT_EQ(s.layout_version(), v);
  s.permute({3, 2, 1, 0});
  EXPECT_NE(s.layout_version(), v);
  v = s.layout_version();
  s.compact({1, 0, 1, 1});
  EXPECT_NE(s.layout_version(), v);
  v = s.layout_version();
  const ballista::FieldStore other = s;
  s.append_from(other, {0});
  EXPECT_NE(s.layout_version(), v);
  v = s.layout_version();
  s.resize(2);
  EXPECT_NE(s.layout_version(), v);
}

TEST(FieldStore, PackedPointsAppendToAStoreWithTheSameFields) {
  // What migrating points between ranks does (points/point_exchange.hpp): pack some points, append
  // them elsewhere; every real and integer component arrives unchanged, in the packed order.
  FieldStore a;
  a.add_real("x", 3, "m");
  a.add_int("id", 1, "1");
  a.add_real("mass", 1, "kg");
  a.resize(4);
  for (Index p = 0; p < 4; ++p) {
    for (int c = 0; c < 3; ++c) a.real("x")[3 * p + c] = 10.0 * p + c + 0.125;
    a.ints("id")[p] = 1000 + p;
    a.real("mass")[p] = -1.0 / (p + 1);
  }
  const std::vector<char> bytes = a.pack({3, 1});
  EXPECT_EQ(bytes.size(), 2u * 5u * 8u);
  FieldStore b = a.empty_like();
  b.resize(1);
  b.ints("id")[0] = 7;
  b.append_packed(bytes.data(), bytes.size());
  ASSERT_EQ(b.size(), 3);
  EXPECT_EQ(b.ints("id")[0], 7);
  EXPECT_EQ(b.ints("id")[1], 1003);
  EXPECT_EQ(b.ints("id")[2], 1001);
  EXPECT_EQ(b.real("x")[3 * 1 + 2], 32.125);
  EXPECT_EQ(b.real("x")[3 * 2 + 0], 10.125);
  EXPECT_EQ(b.real("mass")[2], -0.5);
  // Bytes that are not whole points are refused.
  EXPECT_THROW(b.append_packed(bytes.data(), bytes.size() - 8), Error);
}

}  // namespace test_field_store
