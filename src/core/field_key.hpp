#pragma once
// Typed names of FieldStore fields (the idea of Cabana's Field::Position with its label()).
// A key is a compile-time constant holding the field's name, which is also its HDF5 dataset
// name; its value type T fixes the field's storage type and component count, so a lookup through
// a key is spelled once and cannot ask for the wrong shape:
//   inline constexpr FieldKey<Vec3> kVelocity{"v"};
//   Vec3* v = store.view(kVelocity);            // instead of store.view<Vec3>("v")
//   store.declare(kVelocity, "m/s");            // add_real("v", 3, "m/s")
// Fields whose names are data (material state variables, the deck's output.fields, load_area_<k>)
// keep the string API of FieldStore.
#include <cstdint>
#include <type_traits>

#include "core/tensor.hpp"

namespace ballista {

enum class FieldType { Real, Int };

/// The value types a field can hold: doubles (one per component) or 64-bit integers.
template <class T>
concept FieldValue = std::is_same_v<T, double> || std::is_same_v<T, Vec3> ||
    std::is_same_v<T, Mat3> || std::is_same_v<T, std::int64_t>;

template <FieldValue T>
class FieldKey {
 public:
  using value_type = T;
  /// The type of one component (what add_real / add_int store).
  using scalar_type = std::conditional_t<std::is_same_v<T, std::int64_t>, std::int64_t, double>;
  static constexpr FieldType type =
      std::is_same_v<T, std::int64_t> ? FieldType::Int : FieldType::Real;
  /// Components per point: 1 for double and std::int64_t, 3 for Vec3, 9 for Mat3.
  static constexpr int ncomp = static_cast<int>(sizeof(T) / sizeof(scalar_type));

  constexpr explicit FieldKey(const char* name) : name_(name) {}
  /// The field's name (and dataset name); a string literal, valid for the program's lifetime.
  constexpr const char* name() const { return name_; }

 private:
  const char* name_;
};

static_assert(FieldKey<Vec3>::ncomp == 3 && FieldKey<Mat3>::ncomp == 9,
              "Vec3 and Mat3 must be plain doubles");

}  // namespace ballista
