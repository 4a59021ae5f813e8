#pragma once
// The complete state of a run as named arrays, for checkpoint and restart (docs/restart.md).
// Every part of the state (run loop, points, solver, probes, writers) puts its
// values under its own key prefix ("points.", "mpm.", "run.", ...); io/checkpoint_file writes the
// archive to one HDF5 file and reads it back. Values are exact doubles and integers, so a
// restarted run continues bitwise as the uninterrupted one. A missing key or an array of the
// wrong length is an Error that names the key (a checkpoint of another deck or version).
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include "core/field_store.hpp"

namespace ballista {

class StateArchive {
 public:
  void put(const std::string& key, std::vector<double> values) { reals_[key] = std::move(values); }
  void put(const std::string& key, std::vector<std::int64_t> values) { ints_[key] = std::move(values); }
  void put_real(const std::string& key, double v) { reals_[key] = {v}; }
  void put_int(const std::string& key, std::int64_t v) { ints_[key] = {v}; }
  void put_text(const std::string& key, std::string text) { texts_[key] = std::move(text); }

  bool has(const std::string& key) const {
    return reals_.count(key) || ints_.count(key) || texts_.count(key);
  }
  const std::vector<double>& reals(const std::string& key) const;
  const std::vector<std::int64_t>& ints(const std::string& key) const;
  /// A real array that must hold exactly n values.
  const std::vector<double>& reals(const std::string& key, std::size_t n) const;
  const std::vector<std::int64_t>& ints(const std::string& key, std::size_t n) const;
  double real(const std::string& key) const { return reals(key, 1)[0]; }
  /// A group of scalars saved together under one key, read back into the variables it was made
  /// of, in the order they were put: the reader names each variable once instead of a position.
  void get_into(const std::string& key, std::initializer_list<double*> out) const {
    const std::vector<double>& v = reals(key, out.size());
    std::size_t i = 0;
    for (double* o : out) *o = v[i++];
  }
  /// The same for integer counters (each converted back to its variable's type).
  template <class... T>
  void get_integers_into(const std::string& key, T&... out) const {
    const std::vector<std::int64_t>& v = ints(key, sizeof...(T));
    std::size_t i = 0;
    ((out = static_cast<T>(v[i++])), ...);
  }
  std::int64_t integer(const std::string& key) const { return ints(key, 1)[0]; }
  const std::string& text(const std::string& key) const;

  /// Arrays of fixed-size records of doubles (Vec3, Mat3) as flat real arrays, and integer-like
  /// arrays (uint8 flags, int32 indices) as int64 arrays; get_* resize `out`.
  template <class T>
  void put_records(const std::string& key, const std::vector<T>& v) {
    constexpr std::size_t k = sizeof(T) / sizeof(double);
    static_assert(k * sizeof(double) == sizeof(T), "a record of doubles");
    std::vector<double> flat(k * v.size());
    if (!v.empty()) std::memcpy(flat.data(), v.data(), flat.size() * sizeof(double));
    put(key, std::move(flat));
  }
  /// `count` (if given): the number of records the archive must hold.
  template <class T>
  void get_records(const std::string& key, std::vector<T>& out, std::size_t count = SIZE_MAX) const {
    constexpr std::size_t k = sizeof(T) / sizeof(double);
    const auto& flat = count == SIZE_MAX ? reals(key) : reals(key, k * count);
    if (flat.size() % k != 0) throw_bad_records(key, flat.size(), k);
    out.resize(flat.size() / k);
    if (!out.empty()) std::memcpy(out.data(), flat.data(), flat.size() * sizeof(double));
  }
  template <class T>
  void put_integers(const std::string& key, const std::vector<T>& v) {
    put(key, std::vector<std::int64_t>(v.begin(), v.end()));
  }
  template <class T>
  void get_integers(const std::string& key, std::vector<T>& out, std::size_t count = SIZE_MAX) const {
    const auto& v = count == SIZE_MAX ? ints(key) : ints(key, count);
    out.assign(v.begin(), v.end());
  }

  /// Every field of `store` under prefix + field name, and its size under prefix + "size".
  void put_fields(const std::string& prefix, const FieldStore& store);
  /// Resizes `store` (its fields already declared, as by the same deck) and fills every field
  /// from the archive; a field the archive lacks or whose shape differs is an Error.
  void get_fields(const std::string& prefix, FieldStore& store) const;

  const std::map<std::string, std::vector<double>>& all_reals() const { return reals_; }
  const std::map<std::string, std::vector<std::int64_t>>& all_ints() const { return ints_; }
  const std::map<std::string, std::string>& all_texts() const { return texts_; }

 private:
  std::map<std::string, std::vector<double>> reals_;
  std::map<std::string, std::vector<std::int64_t>> ints_;
  std::map<std::string, std::string> texts_;
  [[noreturn]] static void throw_bad_records(const std::string& key, std::size_t n, std::size_t k);
};

}  // namespace ballista
