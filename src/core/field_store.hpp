#pragma once
// Structure-of-arrays storage for points (MPM particles, PD points, OTM material points).
// Each field has a name (also its output dataset name), a component count, a unit and a type.
// Components of one point are contiguous (x,y,z of a position; 9 entries of F), so a kernel
// reads a Vec3 or Mat3 with one load; different fields live in different arrays.
// Pointers from real()/ints()/view() are invalidated by resize, append, permute and compact.
// Fields with a fixed name are reached through typed keys (core/field_key.hpp; the common point
// fields are in core/point_fields.hpp); the string overloads serve names that are data.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/field_key.hpp"
#include "core/parallel.hpp"

namespace ballista {

struct FieldInfo {
  std::string name;    ///< dataset name
  int ncomp = 1;       ///< components per point
  FieldType type = FieldType::Real;
  std::string unit;    ///< SI unit, "1" for dimensionless
  bool output = true;  ///< written to the HDF5 output
};

class FieldStore {
 public:
  /// Declares a real field (idempotent if the same name/ncomp already exists).
  void add_real(const std::string& name, int ncomp, const std::string& unit, bool output = true,
                double initial = 0.0);
  void add_int(const std::string& name, int ncomp, const std::string& unit, bool output = true,
               std::int64_t initial = 0);
  bool has(const std::string& name) const { return find(name) >= 0; }

  // ---- typed keys: the shape comes from the key's type (a mismatch with a field declared by
  // name under the same name throws, like view<T>(name)) --------------------------------------
  /// Declares the key's field: real with FieldKey<T>::ncomp components, or integer (idempotent).
  template <class T>
  void declare(const FieldKey<T>& key, const std::string& unit, bool output = true,
               typename FieldKey<T>::scalar_type initial = 0) {
    if constexpr (FieldKey<T>::type == FieldType::Int)
      add_int(key.name(), FieldKey<T>::ncomp, unit, output, initial);
    else
      add_real(key.name(), FieldKey<T>::ncomp, unit, output, initial);
  }
  /// Whether a field of the key's name is declared (whatever its shape, like has(name)).
  template <class T>
  bool has(const FieldKey<T>& key) const { return find(key.name()) >= 0; }
  /// Whether a field of the key's name has the key's type and component count.
  template <class T>
  bool has_shape(const FieldKey<T>& key) const {
    const int k = find(key.name());
    return k >= 0 && info_[k].type == FieldKey<T>::type && info_[k].ncomp == FieldKey<T>::ncomp;
  }
  template <class T>
  T* view(const FieldKey<T>& key) {
    return static_cast<T*>(data(key.name(), FieldKey<T>::type, FieldKey<T>::ncomp));
  }
  template <class T>
  const T* view(const FieldKey<T>& key) const {
    return static_cast<const T*>(data(key.name(), FieldKey<T>::type, FieldKey<T>::ncomp));
  }
  double* real(const FieldKey<double>& key) { return view(key); }
  const double* real(const FieldKey<double>& key) const { return view(key); }
  std::int64_t* ints(const FieldKey<std::int64_t>& key) { return view(key); }
  const std::int64_t* ints(const FieldKey<std::int64_t>& key) const { return view(key); }
  template <class T>
  const FieldInfo& info(const FieldKey<T>& key) const {
    return info_[data_index(key.name(), FieldKey<T>::type, FieldKey<T>::ncomp)];
  }
  template <class T>
  void set_output(const FieldKey<T>& key, bool output) {
    info_[data_index(key.name(), FieldKey<T>::type, FieldKey<T>::ncomp)].output = output;
  }

  Index size() const { return size_; }
  /// Changes whenever points may have changed places or number (resize, permute, compact,
  /// append): a cache of point indices built at one version is valid while it stays the same.
  std::uint64_t layout_version() const { return layout_version_; }
  void resize(Index n);

  double* real(const std::string& name);
  const double* real(const std::string& name) const;
  std::int64_t* ints(const std::string& name);
  const std::int64_t* ints(const std::string& name) const;

  /// Typed view of a real field whose ncomp matches sizeof(T)/sizeof(double) (Vec3, Mat3, double).
  template <class T>
  T* view(const std::string& name) {
    check_ncomp(name, static_cast<int>(sizeof(T) / sizeof(double)));
    return reinterpret_cast<T*>(real(name));
  }
  template <class T>
  const T* view(const std::string& name) const {
    check_ncomp(name, static_cast<int>(sizeof(T) / sizeof(double)));
    return reinterpret_cast<const T*>(real(name));
  }

  const std::vector<FieldInfo>& fields() const { return info_; }
  /// Bytes one point occupies over every declared field (8 per component).
  double bytes_per_point() const {
    double b = 0.0;
    for (const auto& f : info_) b += 8.0 * f.ncomp;
    return b;
  }
  const FieldInfo& info(const std::string& name) const;
  /// Whether a declared field is written to the output (a solver clears it for a common field its
  /// points never update, which would only carry placeholders).
  void set_output(const std::string& name, bool output);

  /// Reorders every field: new point i is old point order[i].
  void permute(const std::vector<Index>& order);
  /// Keeps the points with keep[i] != 0, in order.
  void compact(const std::vector<char>& keep);
  /// Appends points `which` of `other`, which must declare the same fields in the same order.
  void append_from(const FieldStore& other, const std::vector<Index>& which);
  /// An empty store with the same field declarations.
  FieldStore empty_like() const;
  /// Points `which` as bytes, field after field in declaration order (8 bytes per component):
  /// what a rank sends when points migrate or are gathered for output.
  std::vector<char> pack(const std::vector<Index>& which) const;
  /// Appends points packed by pack() of a store with the same declarations.
  void append_packed(const char* data, std::size_t bytes);

 private:
  void add_field(const std::string& name, int ncomp, FieldType type, const std::string& unit, bool output,
                 double real_initial, std::int64_t int_initial);
  int find(std::string_view name) const;
  /// Index of the field `name`, which must have this type and component count (else throws).
  std::size_t data_index(std::string_view name, FieldType type, int ncomp) const;
  void* data(std::string_view name, FieldType type, int ncomp);
  const void* data(std::string_view name, FieldType type, int ncomp) const;
  void check_ncomp(const std::string& name, int ncomp) const;

  Index size_ = 0;
  std::uint64_t layout_version_ = 0;
  std::vector<FieldInfo> info_;
  std::vector<std::vector<double>> real_;        // indexed like info_ (empty if Int)
  std::vector<std::vector<std::int64_t>> int_;   // indexed like info_ (empty if Real)
  std::vector<double> real_init_;
  std::vector<double> real_scratch_;      // reused by permute
  std::vector<std::int64_t> int_scratch_;
  std::vector<std::int64_t> int_init_;
};

}  // namespace ballista
