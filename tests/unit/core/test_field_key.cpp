// FieldKey: a typed field name. A field declared through a key is the same field its name reaches
// through the string API (same pointer, shape from the key's type), and a key of the wrong shape
// is refused instead of reinterpreting the data.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "core/field_key.hpp"
#include "core/field_store.hpp"
#include "core/point_fields.hpp"
#include "core/tensor.hpp"

namespace test_field_key {

using namespace ballista;

namespace {

constexpr FieldKey<double> kScalar{"scalar"};
constexpr FieldKey<Vec3> kVector{"vector"};
constexpr FieldKey<Mat3> kTensor{"tensor"};
constexpr FieldKey<std::int64_t> kCount{"count"};

// The key is a compile-time constant: its name, type and component count are known at compile time.
static_assert(std::string_view(kVector.name()) == "vector");
static_assert(FieldKey<double>::ncomp == 1 && FieldKey<double>::type == FieldType::Real);
static_assert(FieldKey<Vec3>::ncomp == 3 && FieldKey<Vec3>::type == FieldType::Real);
static_assert(FieldKey<Mat3>::ncomp == 9 && FieldKey<Mat3>::type == FieldType::Real);
static_assert(FieldKey<std::int64_t>::ncomp == 1 && FieldKey<std::int64_t>::type == FieldType::Int);

TEST(FieldKey, NameIsTheLabel) {
  EXPECT_EQ(std::string(kScalar.name()), "scalar");
  EXPECT_EQ(std::string(kPosition.name()), "x");
  EXPECT_EQ(std::string(kVelocity.name()), "v");
  EXPECT_EQ(std::string(kDeformationGradient.name()), "F");
  EXPECT_EQ(std::string(kBodyIndex.name()), "body");
}

TEST(FieldKey, DeclaresTheShapeOfItsType) {
  FieldStore s;
  s.declare(kScalar, "m");
  s.declare(kVector, "m/s", false);
  s.declare(kTensor, "Pa", true, 2.5);
  s.declare(kCount, "1", true, std::int64_t{-1});
  ASSERT_EQ(s.fields().size(), 4u);
  const FieldInfo& v = s.info(kVector);
  EXPECT_EQ(v.name, "vector");
  EXPECT_EQ(v.ncomp, 3);
  EXPECT_EQ(v.type, FieldType::Real);
  EXPECT_EQ(v.unit, "m/s");
  EXPECT_FALSE(v.output);
  EXPECT_EQ(s.info("scalar").ncomp, 1);
  EXPECT_EQ(s.info("tensor").ncomp, 9);
  EXPECT_EQ(s.info("count").ncomp, 1);
  EXPECT_EQ(s.info("count").type, FieldType::Int);
  // Declaration order is the order of the calls (it is the packing order of migrated points).
  EXPECT_EQ(s.fields()[0].name, "scalar");
  EXPECT_EQ(s.fields()[3].name, "count");
  // Idempotent, like add_real / add_int.
  s.declare(kVector, "m/s");
  EXPECT_EQ(s.fields().size(), 4u);
  // Initial values.
  s.resize(2);
  EXPECT_EQ(s.view(kTensor)[1].a[8], 2.5);
  EXPECT_EQ(s.ints(kCount)[1], -1);
}

TEST(FieldKey, ReachesTheSameStorageAsTheName) {
  FieldStore s;
  s.declare(kScalar, "m");
  s.declare(kVector, "m/s");
  s.declare(kTensor, "Pa");
  s.declare(kCount, "1");
  s.resize(3);
  EXPECT_EQ(s.view(kScalar), s.real("scalar"));
  EXPECT_EQ(s.real(kScalar), s.real("scalar"));
  EXPECT_EQ(s.view(kVector), s.view<Vec3>("vector"));
  EXPECT_EQ(s.view(kTensor), s.view<Mat3>("tensor"));
  EXPECT_EQ(s.view(kCount), s.ints("count"));
  EXPECT_EQ(s.ints(kCount), s.ints("count"));
  const FieldStore& c = s;
  EXPECT_EQ(c.view(kVector), c.view<Vec3>("vector"));
  EXPECT_EQ(c.ints(kCount), c.ints("count"));
  EXPECT_TRUE(s.has(kVector));
  EXPECT_FALSE(s.has(kPosition));
  s.set_output(kTensor, false);
  EXPECT_FALSE(s.info("tensor").output);
}

TEST(FieldKey, AFieldOfAnotherShapeIsRefused) {
  FieldStore s;
  s.add_real("x", 1, "m");        // a scalar under the name of kPosition (a Vec3)
  s.add_real("body", 1, "1");     // a real field under the name of kBodyIndex (integer)
  EXPECT_TRUE(s.has(kPosition));  // has() asks for the name only, like has(name)
  EXPECT_FALSE(s.has_shape(kPosition));
  EXPECT_FALSE(s.has_shape(kBodyIndex));
  EXPECT_FALSE(s.has_shape(kVelocity));
  EXPECT_THROW(s.view(kVelocity), Error);  // not declared
  s.add_real("v", 3, "m/s");
  EXPECT_TRUE(s.has_shape(kVelocity));
  s.add_int("id", 1, "1");
  EXPECT_TRUE(s.has_shape(kId));
  EXPECT_THROW(s.view(kPosition), Error);
  EXPECT_THROW(s.ints(kBodyIndex), Error);
  EXPECT_THROW(s.declare(kPosition, "m"), Error);
}

}  // namespace

}  // namespace test_field_key
