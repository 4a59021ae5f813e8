#include "points/point_exchange.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "core/point_fields.hpp"

namespace ballista {

Index migrate_points(const Communicator& comm, FieldStore& store, const std::vector<int>& dest) {
  if (!comm.distributed()) return 0;
  const int me = comm.rank(), size = comm.size();
  const Index n = store.size();
  std::vector<std::vector<Index>> out(size);
  std::vector<char> keep(static_cast<std::size_t>(n), 1);
  Index sent = 0;
  for (Index p = 0; p < n; ++p)
    if (dest[p] != me) {
      out[dest[p]].push_back(p);
      keep[p] = 0;
      ++sent;
    }
  std::vector<std::vector<char>> send(size);
  for (int r = 0; r < size; ++r)
    if (!out[r].empty()) send[r] = store.pack(out[r]);
  const std::vector<std::vector<char>> recv = comm.all_to_all(send);
  if (sent > 0) store.compact(keep);
  Index received = 0;
  const std::size_t per = static_cast<std::size_t>(store.bytes_per_point());
  for (int r = 0; r < size; ++r) {
    if (recv[r].empty()) continue;
    store.append_packed(recv[r].data(), recv[r].size());
    received += static_cast<Index>(recv[r].size() / per);
  }
  return sent + received;
}

FieldStore gather_points(const Communicator& comm, const FieldStore& store, int root, bool by_id) {
  FieldStore all = store.empty_like();
  std::vector<Index> every(static_cast<std::size_t>(store.size()));
  std::iota(every.begin(), every.end(), Index{0});
  const std::vector<std::vector<char>> parts = comm.gather(store.pack(every), root);
  if (comm.rank() != root) return all;
  for (const auto& part : parts) all.append_packed(part.data(), part.size());
  if (!by_id) return all;
  const std::int64_t* id = all.ints(kId);
  std::vector<Index> order(static_cast<std::size_t>(all.size()));
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return id[a] < id[b]; });
  all.permute(order);
  return all;
}

}  // namespace ballista

namespace ballista {

std::vector<double> gather_values(const Communicator& comm, const std::vector<double>& mine, int root) {
  std::vector<char> bytes(mine.size() * sizeof(double));
  if (!mine.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
  std::vector<double> out;
  for (const auto& part : comm.gather(bytes, root)) {
    const std::size_t n0 = out.size();
    out.resize(n0 + part.size() / sizeof(double));
    if (!part.empty()) std::memcpy(out.data() + n0, part.data(), part.size());
  }
  return out;
}

}  // namespace ballista
