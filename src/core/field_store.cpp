#include "core/field_store.hpp"

#include <cstring>

#include <algorithm>

#include "core/error.hpp"

namespace ballista {

int FieldStore::find(std::string_view name) const {
  for (size_t k = 0; k < info_.size(); ++k)
    if (info_[k].name == name) return static_cast<int>(k);
  return -1;
}

namespace {
std::string shape_text(FieldType type, int ncomp) {
  return std::to_string(ncomp) + (type == FieldType::Real ? " real" : " integer") +
         (ncomp == 1 ? " component" : " components");
}
}  // namespace

std::size_t FieldStore::data_index(std::string_view name, FieldType type, int ncomp) const {
  const int k = find(name);
  if (k < 0) throw Error("no field named '" + std::string(name) + "'");
  const FieldInfo& fi = info_[static_cast<std::size_t>(k)];
  if (fi.type != type || fi.ncomp != ncomp)
    throw Error("field '" + fi.name + "' has " + shape_text(fi.type, fi.ncomp) + ", its key " +
                shape_text(type, ncomp));
  return static_cast<std::size_t>(k);
}

void* FieldStore::data(std::string_view name, FieldType type, int ncomp) {
  const std::size_t k = data_index(name, type, ncomp);
  if (type == FieldType::Real) return real_[k].data();
  return int_[k].data();
}
const void* FieldStore::data(std::string_view name, FieldType type, int ncomp) const {
  return const_cast<FieldStore*>(this)->data(name, type, ncomp);
}

void FieldStore::check_ncomp(const std::string& name, int ncomp) const {
  const FieldInfo& fi = info(name);
  if (fi.type != FieldType::Real || fi.ncomp != ncomp)
    throw Error("field '" + name + "' has " + std::to_string(fi.ncomp) +
                " components, a view of " + std::to_string(ncomp) + " was requested");
}

void FieldStore::set_output(const std::string& name, bool output) {
  const int k = find(name);
  if (k < 0) throw Error("no field named '" + name + "'");
  info_[static_cast<std::size_t>(k)].output = output;
}

const FieldInfo& FieldStore::info(const std::string& name) const {
  const int k = find(name);
  if (k < 0) throw Error("no field named '" + name + "'");
  return info_[k];
}

void FieldStore::add_real(const std::string& name, int ncomp, const std::string& unit, bool output,
                          double initial) {
  add_field(name, ncomp, FieldType::Real, unit, output, initial, 0);
}

void FieldStore::add_int(const std::string& name, int ncomp, const std::string& unit, bool output,
                         std::int64_t initial) {
  add_field(name, ncomp, FieldType::Int, unit, output, 0.0, initial);
}

void FieldStore::add_field(const std::string& name, int ncomp, FieldType type, const std::string& unit, bool output,
                           double real_initial, std::int64_t int_initial) {
  const int k = find(name);
  if (k >= 0) {
    if (info_[k].ncomp != ncomp || info_[k].type != type)
      throw Error("field '" + name + "' declared twice with different shapes");
    return;
  }
  // Both value arrays exist for every field (the other one empty), so a field's index is the same
  // in each.
  const bool real = type == FieldType::Real;
  info_.push_back({name, ncomp, type, unit, output});
  real_.emplace_back(real ? static_cast<size_t>(size_ * ncomp) : 0, real_initial);
  int_.emplace_back(real ? 0 : static_cast<size_t>(size_ * ncomp), int_initial);
  real_init_.push_back(real_initial);
  int_init_.push_back(int_initial);
}

void FieldStore::resize(Index n) {
  ++layout_version_;
  for (size_t k = 0; k < info_.size(); ++k) {
    const size_t len = static_cast<size_t>(n * info_[k].ncomp);
    if (info_[k].type == FieldType::Real)
      real_[k].resize(len, real_init_[k]);
    else
      int_[k].resize(len, int_init_[k]);
  }
  size_ = n;
}

double* FieldStore::real(const std::string& name) {
  const int k = find(name);
  if (k < 0 || info_[k].type != FieldType::Real) throw Error("no real field named '" + name + "'");
  return real_[k].data();
}
const double* FieldStore::real(const std::string& name) const {
  return const_cast<FieldStore*>(this)->real(name);
}
std::int64_t* FieldStore::ints(const std::string& name) {
  const int k = find(name);
  if (k < 0 || info_[k].type != FieldType::Int) throw Error("no integer field named '" + name + "'");
  return int_[k].data();
}
const std::int64_t* FieldStore::ints(const std::string& name) const {
  return const_cast<FieldStore*>(this)->ints(name);
}

namespace {
/// Permutes through a scratch buffer that is reused across calls (no allocation per sort).
template <class T>
void permute_array(std::vector<T>& a, int nc, const std::vector<Index>& order, std::vector<T>& out) {
  out.resize(order.size() * nc);
  const Index n = static_cast<Index>(order.size());
  // The copy back is split over the threads as the gather is, in the same region and static split,
  // so each thread copies back what it gathered (one thread copying it was a few per cent of a
  // multi-rate step, which reorders every step). In place: views into the field stay valid.
  T* const to = out.data();
  T* const from = a.data();
  const Index* const idx = order.data();
#pragma omp parallel if (n > kParallelThreshold)
  {
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i)
      for (int c = 0; c < nc; ++c) to[i * nc + c] = from[idx[i] * nc + c];
    // Each thread copies one contiguous share back with the library's block copy (an element
    // loop is slower on one thread than std::copy's memmove).
#ifdef _OPENMP
    const int nt = omp_get_num_threads(), t = omp_get_thread_num();
#else
    const int nt = 1, t = 0;
#endif
    const Index b = static_run_begin(n, nt, t), e = static_run_begin(n, nt, t + 1);
    std::copy(to + b * nc, to + e * nc, from + b * nc);
  }
}
template <class T>
void compact_array(std::vector<T>& a, int nc, const std::vector<char>& keep) {
  size_t w = 0;
  for (size_t i = 0; i < keep.size(); ++i) {
    if (!keep[i]) continue;
    for (int c = 0; c < nc; ++c) a[w * nc + c] = a[i * nc + c];
    ++w;
  }
  a.resize(w * nc);
}
}  // namespace

void FieldStore::permute(const std::vector<Index>& order) {
  ++layout_version_;
  if (static_cast<Index>(order.size()) != size_) throw Error("permute: order has the wrong size");
  for (size_t k = 0; k < info_.size(); ++k) {
    if (info_[k].type == FieldType::Real)
      permute_array(real_[k], info_[k].ncomp, order, real_scratch_);
    else
      permute_array(int_[k], info_[k].ncomp, order, int_scratch_);
  }
}

void FieldStore::compact(const std::vector<char>& keep) {
  ++layout_version_;
  if (static_cast<Index>(keep.size()) != size_) throw Error("compact: mask has the wrong size");
  Index n = 0;
  for (char k : keep) n += k ? 1 : 0;
  for (size_t k = 0; k < info_.size(); ++k) {
    if (info_[k].type == FieldType::Real)
      compact_array(real_[k], info_[k].ncomp, keep);
    else
      compact_array(int_[k], info_[k].ncomp, keep);
  }
  size_ = n;
}

void FieldStore::append_from(const FieldStore& other, const std::vector<Index>& which) {
  ++layout_version_;
  if (other.info_.size() != info_.size()) throw Error("append_from: field layouts differ");
  // Check the whole layout before growing, so a refused append leaves this store unchanged.
  for (size_t k = 0; k < info_.size(); ++k)
    if (other.info_[k].name != info_[k].name || other.info_[k].ncomp != info_[k].ncomp ||
        other.info_[k].type != info_[k].type)
      throw Error("append_from: field '" + info_[k].name + "' differs");
  for (Index q : which)
    if (q < 0 || q >= other.size_) throw Error("append_from: point index out of range");
  const Index n0 = size_;
  resize(size_ + static_cast<Index>(which.size()));
  for (size_t k = 0; k < info_.size(); ++k) {
    const int nc = info_[k].ncomp;
    for (size_t q = 0; q < which.size(); ++q)
      for (int c = 0; c < nc; ++c) {
        const size_t dst = (n0 + q) * nc + c, src = which[q] * nc + c;
        if (info_[k].type == FieldType::Real)
          real_[k][dst] = other.real_[k][src];
        else
          int_[k][dst] = other.int_[k][src];
      }
  }
}

std::vector<char> FieldStore::pack(const std::vector<Index>& which) const {
  double per_point = bytes_per_point();
  std::vector<char> out(static_cast<std::size_t>(per_point) * which.size());
  char* o = out.data();
  for (size_t k = 0; k < info_.size(); ++k) {
    const std::size_t nc = static_cast<std::size_t>(info_[k].ncomp);
    const char* base = info_[k].type == FieldType::Real ? reinterpret_cast<const char*>(real_[k].data())
                                                        : reinterpret_cast<const char*>(int_[k].data());
    for (Index q : which) {
      std::memcpy(o, base + static_cast<std::size_t>(q) * nc * 8, nc * 8);
      o += nc * 8;
    }
  }
  return out;
}

void FieldStore::append_packed(const char* data, std::size_t bytes) {
  const std::size_t per_point = static_cast<std::size_t>(bytes_per_point());
  if (bytes == 0) return;
  if (per_point == 0 || bytes % per_point != 0) throw Error("append_packed: the bytes do not hold whole points");
  const Index m = static_cast<Index>(bytes / per_point);
  const Index n0 = size_;
  resize(size_ + m);
  const char* in = data;
  for (size_t k = 0; k < info_.size(); ++k) {
    const std::size_t nc = static_cast<std::size_t>(info_[k].ncomp);
    char* base = info_[k].type == FieldType::Real ? reinterpret_cast<char*>(real_[k].data())
                                                  : reinterpret_cast<char*>(int_[k].data());
    const std::size_t len = static_cast<std::size_t>(m) * nc * 8;
    std::memcpy(base + static_cast<std::size_t>(n0) * nc * 8, in, len);
    in += len;
  }
}

FieldStore FieldStore::empty_like() const {
  // The declarations only: copying the points first would cost a whole store per call (the
  // gathers of an MPI run make one per output).
  FieldStore s;
  s.info_ = info_;
  s.real_init_ = real_init_;
  s.int_init_ = int_init_;
  s.real_.resize(real_.size());
  s.int_.resize(int_.size());
  return s;
}

}  // namespace ballista
