#include "core/state_archive.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace ballista {

namespace {

[[noreturn]] void missing(const std::string& key, const char* kind) {
  throw Error("the checkpoint has no " + std::string(kind) + " '" + key +
              "' (written by another deck, solver or version of ballista?)");
}

[[noreturn]] void wrong_size(const std::string& key, std::size_t have, std::size_t want) {
  throw Error("the checkpoint's '" + key + "' holds " + std::to_string(have) + " values, " + std::to_string(want) +
              " were expected (written by another deck or version of ballista?)");
}

}  // namespace

const std::vector<double>& StateArchive::reals(const std::string& key) const {
  const auto it = reals_.find(key);
  if (it == reals_.end()) missing(key, "real array");
  return it->second;
}

const std::vector<std::int64_t>& StateArchive::ints(const std::string& key) const {
  const auto it = ints_.find(key);
  if (it == ints_.end()) missing(key, "integer array");
  return it->second;
}

const std::vector<double>& StateArchive::reals(const std::string& key, std::size_t n) const {
  const auto& v = reals(key);
  if (v.size() != n) wrong_size(key, v.size(), n);
  return v;
}

const std::vector<std::int64_t>& StateArchive::ints(const std::string& key, std::size_t n) const {
  const auto& v = ints(key);
  if (v.size() != n) wrong_size(key, v.size(), n);
  return v;
}

const std::string& StateArchive::text(const std::string& key) const {
  const auto it = texts_.find(key);
  if (it == texts_.end()) missing(key, "text");
  return it->second;
}

void StateArchive::throw_bad_records(const std::string& key, std::size_t n, std::size_t k) {
  throw Error("the checkpoint's '" + key + "' holds " + std::to_string(n) + " values, not a multiple of " +
              std::to_string(k) + " (written by another version of ballista?)");
}

void StateArchive::put_fields(const std::string& prefix, const FieldStore& store) {
  const Index n = store.size();
  put_int(prefix + "size", n);
  for (const FieldInfo& f : store.fields()) {
    const std::size_t len = static_cast<std::size_t>(n) * f.ncomp;
    if (f.type == FieldType::Real) {
      const double* d = store.real(f.name);
      put(prefix + f.name, std::vector<double>(d, d + len));
    } else {
      const std::int64_t* d = store.ints(f.name);
      put(prefix + f.name, std::vector<std::int64_t>(d, d + len));
    }
  }
}

void StateArchive::get_fields(const std::string& prefix, FieldStore& store) const {
  const std::int64_t n = integer(prefix + "size");
  if (n < 0) wrong_size(prefix + "size", 0, 1);
  store.resize(static_cast<Index>(n));
  for (const FieldInfo& f : store.fields()) {
    const std::size_t len = static_cast<std::size_t>(n) * f.ncomp;
    if (f.type == FieldType::Real) {
      const auto& v = reals(prefix + f.name, len);
      std::copy(v.begin(), v.end(), store.real(f.name));
    } else {
      const auto& v = ints(prefix + f.name, len);
      std::copy(v.begin(), v.end(), store.ints(f.name));
    }
  }
}

}  // namespace ballista
