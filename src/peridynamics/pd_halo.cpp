#include "peridynamics/pd_halo.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <unordered_map>

#include "core/error.hpp"

namespace ballista::pd {

namespace {

/// Values as bytes (the byte messages of Communicator::all_to_all).
template <class T>
void append(std::vector<char>& buf, const T& v) {
  const auto at = buf.size();
  buf.resize(at + sizeof(T));
  std::memcpy(buf.data() + at, &v, sizeof(T));
}
template <class T>
T read(const std::vector<char>& buf, std::size_t& at) {
  T v;
  std::memcpy(&v, buf.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

}  // namespace

void LocalPoints::push(std::int64_t i, std::int64_t b, std::int64_t m, const Vec3& r0,
                       const Vec3& r, double v0, bool is_own) {
  if (is_own) own.push_back(size());
  id.push_back(i);
  body.push_back(b);
  material.push_back(m);
  x0.push_back(r0);
  x.push_back(r);
  vol0.push_back(v0);
  ghost.push_back(is_own ? 0 : 1);
}

void LocalPoints::truncate(Index n) {
  const auto m = static_cast<std::size_t>(n);
  id.resize(m), body.resize(m), material.resize(m), x0.resize(m), x.resize(m), vol0.resize(m),
      ghost.resize(m);
}

void PdHalo::plan_bond_ghosts(const Communicator& comm, const LocalPoints& local,
                              const std::vector<int>& owner) {
  ranks_ = comm.size();
  const auto P = static_cast<std::size_t>(ranks_);
  bond_send_.assign(P, {});
  bond_recv_.assign(P, {});
  contact_send_.assign(P, {});
  contact_recv_.assign(P, {});
  if (!comm.distributed()) return;
  // Ask every owner for its points this rank holds ghosts of (ids, in local order).
  std::vector<std::vector<char>> ask(P);
  for (Index l = 0; l < local.bond_local; ++l)
    if (local.ghost[l]) {
      const int r = owner[l];
      if (r == comm.rank() || r < 0 || r >= ranks_)
        throw Error("PdHalo: a ghost without a valid owner");
      bond_recv_[r].push_back(l);
      append(ask[r], local.id[l]);
    }
  const std::vector<std::vector<char>> asked = comm.all_to_all(ask);
  // Own points are in id order among the local ones: find each asked id by binary search.
  std::vector<std::int64_t> own_ids(local.own.size());
  for (std::size_t i = 0; i < own_ids.size(); ++i) own_ids[i] = local.id[local.own[i]];
  for (std::size_t r = 0; r < P; ++r) {
    std::size_t at = 0;
    while (at < asked[r].size()) {
      const auto want = read<std::int64_t>(asked[r], at);
      const auto it = std::lower_bound(own_ids.begin(), own_ids.end(), want);
      if (it == own_ids.end() || *it != want)
        throw Error("PdHalo: rank " + std::to_string(r) + " asked for point " +
                    std::to_string(want) + ", which this rank does not own");
      bond_send_[r].push_back(local.own[static_cast<std::size_t>(it - own_ids.begin())]);
    }
  }
  bond_sent_ = bond_send_;
  for (auto& v : bond_sent_) std::sort(v.begin(), v.end());
}

void PdHalo::update(const Communicator& comm, LocalPoints& local, std::vector<double>& s0) const {
  if (!comm.distributed()) return;
  const std::vector<int> peer = peers();
  std::vector<std::vector<double>> send(peer.size()), recv(peer.size());
  for (std::size_t k = 0; k < peer.size(); ++k) {
    const int r = peer[k];
    auto& b = send[k];
    b.reserve(4 * bond_send_[r].size() + 3 * contact_send_[r].size());
    for (Index l : bond_send_[r])
      b.insert(b.end(), {local.x[l][0], local.x[l][1], local.x[l][2], s0[l]});
    for (Index l : contact_send_[r])
      b.insert(b.end(), {local.x[l][0], local.x[l][1], local.x[l][2]});
    recv[k].resize(4 * bond_recv_[r].size() + 3 * contact_recv_[r].size());
  }
  comm.exchange(peer, send, recv);
  for (std::size_t k = 0; k < peer.size(); ++k) {
    const int r = peer[k];
    const double* v = recv[k].data();
    for (Index l : bond_recv_[r]) {
      local.x[l] = Vec3{{v[0], v[1], v[2]}};
      s0[l] = v[3];
      v += 4;
    }
    for (Index l : contact_recv_[r]) {
      local.x[l] = Vec3{{v[0], v[1], v[2]}};
      v += 3;
    }
  }
}

void PdHalo::update_bond_values(const Communicator& comm, const LocalPoints&,
                                std::vector<double>& values) const {
  if (!comm.distributed()) return;
  std::vector<int> peer;
  for (int r = 0; r < ranks_; ++r)
    if (!bond_send_[r].empty() || !bond_recv_[r].empty()) peer.push_back(r);
  std::vector<std::vector<double>> send(peer.size()), recv(peer.size());
  for (std::size_t k = 0; k < peer.size(); ++k) {
    for (Index l : bond_send_[peer[k]]) send[k].push_back(values[l]);
    recv[k].resize(bond_recv_[peer[k]].size());
  }
  comm.exchange(peer, send, recv);
  for (std::size_t k = 0; k < peer.size(); ++k)
    for (std::size_t j = 0; j < recv[k].size(); ++j) values[bond_recv_[peer[k]][j]] = recv[k][j];
}

void PdHalo::gather_contact_ghosts(const Communicator& comm, LocalPoints& local, double cutoff,
                                   int dim, const std::uint8_t* skip) {
  if (!comm.distributed()) return;
  const auto P = static_cast<std::size_t>(ranks_);
  local.truncate(local.bond_local);
  contact_send_.assign(P, {});
  contact_recv_.assign(P, {});
  contact_source_.clear();
  contact_slot_.clear();
  // The cells (edge: the cutoff, a hair more, so that no pair at the cutoff is lost to round-off)
  // that hold this rank's own points now: a point of another rank within the cutoff of one of
  // them lies in one of the 3^dim cells around that point's cell. The ranks all-gather their
  // occupied cells, so a rank offers another only its points next to that rank's cells (a bounding
  // box per rank would offer every point between the fragments of a cloud that has spread out).
  const double cell = cutoff * (1.0 + 1e-6);
  constexpr std::int64_t kOff = std::int64_t{1} << 20;  // cell coordinates in [-2^20, 2^20): 21 bits each
  auto coord = [&](double v) {
    return std::clamp(static_cast<std::int64_t>(std::floor(v / cell)), -kOff + 1, kOff - 2);
  };
  auto key = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return ((i + kOff) << 42) | ((j + kOff) << 21) | (k + kOff);
  };
  const int reach_z = dim == 3 ? 1 : 0;  // 2D: the points lie in one plane
  std::vector<std::int64_t> mine;
  for (Index l : local.own)
    if (!(skip && skip[l])) mine.push_back(key(coord(local.x[l][0]), coord(local.x[l][1]), coord(local.x[l][2])));
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  std::vector<int> counts;
  const std::vector<std::int64_t> all = comm.all_gather(mine, counts);
  std::unordered_map<std::int64_t, std::vector<int>> holders;  // cell -> the other ranks with points in it
  holders.reserve(all.size());
  std::size_t at_cell = 0;
  for (int r = 0; r < ranks_; ++r)
    for (int j = 0; j < counts[r]; ++j, ++at_cell)
      if (r != comm.rank()) holders[all[at_cell]].push_back(r);
  // Offer each rank the own points next to its cells that are not its bond ghosts already.
  std::vector<std::vector<char>> offer(P);
  offered_.assign(P, {});
  std::vector<Index> seen(P, -1);  // the point last offered to each rank
  for (Index l : local.own) {
    if (skip && skip[l]) continue;
    const std::int64_t i0 = coord(local.x[l][0]), j0 = coord(local.x[l][1]), k0 = coord(local.x[l][2]);
    for (std::int64_t i = i0 - 1; i <= i0 + 1; ++i)
      for (std::int64_t j = j0 - 1; j <= j0 + 1; ++j)
        for (std::int64_t k = k0 - reach_z; k <= k0 + reach_z; ++k) {
          const auto it = holders.find(key(i, j, k));
          if (it == holders.end()) continue;
          for (int r : it->second) {
            if (seen[r] == l) continue;
            seen[r] = l;
            if (std::binary_search(bond_sent_[r].begin(), bond_sent_[r].end(), l)) continue;  // a bond ghost there
            offered_[r].push_back(l);
            auto& o = offer[r];
            append(o, local.id[l]);
            append(o, local.body[l]);
            append(o, local.material[l]);
            append(o, local.x0[l]);
            append(o, local.x[l]);
            append(o, local.vol0[l]);
          }
        }
  }
  for (const auto& o : offer) offered_bytes_ += static_cast<std::int64_t>(o.size());
  const std::vector<std::vector<char>> got = comm.all_to_all(offer);
  for (int r = 0; r < ranks_; ++r) {
    std::size_t at = 0;
    Index slot = 0;
    while (at < got[r].size()) {
      const auto i = read<std::int64_t>(got[r], at);
      const auto b = read<std::int64_t>(got[r], at);
      const auto m = read<std::int64_t>(got[r], at);
      const auto r0 = read<Vec3>(got[r], at);
      const auto y = read<Vec3>(got[r], at);
      const auto v0 = read<double>(got[r], at);
      local.push(i, b, m, r0, y, v0, false);
      contact_source_.push_back(r);
      contact_slot_.push_back(slot++);
    }
  }
}

std::vector<Index> PdHalo::keep_contact_ghosts(const Communicator& comm, LocalPoints& local,
                                               const std::vector<char>& needed) {
  const Index n = local.size();
  std::vector<Index> renumber(static_cast<std::size_t>(n), -1);
  for (Index l = 0; l < local.bond_local; ++l) renumber[l] = l;
  if (!comm.distributed()) return renumber;
  const auto P = static_cast<std::size_t>(ranks_);
  // Compact the kept contact ghosts in place and tell each source which of its offer are kept.
  std::vector<std::vector<char>> keep_msg(P);
  Index w = local.bond_local;
  for (Index l = local.bond_local; l < n; ++l) {
    if (!needed[l]) continue;
    const std::size_t j = static_cast<std::size_t>(l - local.bond_local);
    const int r = contact_source_[j];
    append(keep_msg[r], static_cast<std::int64_t>(contact_slot_[j]));
    contact_recv_[r].push_back(w);
    renumber[l] = w;
    local.id[w] = local.id[l], local.body[w] = local.body[l], local.material[w] = local.material[l];
    local.x0[w] = local.x0[l], local.x[w] = local.x[l], local.vol0[w] = local.vol0[l],
    local.ghost[w] = 1;
    ++w;
  }
  local.truncate(w);
  const std::vector<std::vector<char>> kept = comm.all_to_all(keep_msg);
  for (std::size_t r = 0; r < P; ++r) {
    std::size_t at = 0;
    while (at < kept[r].size())
      contact_send_[r].push_back(
          offered_[r][static_cast<std::size_t>(read<std::int64_t>(kept[r], at))]);
  }
  offered_.assign(P, {});
  contact_source_.clear();
  contact_slot_.clear();
  return renumber;
}

std::vector<int> PdHalo::peers() const {
  // Symmetric: r is a peer of this rank exactly when this rank is one of r's (each side knows both
  // what it sends and what it receives).
  std::vector<int> out;
  for (int r = 0; r < static_cast<int>(bond_send_.size()); ++r)
    if (!bond_send_[r].empty() || !bond_recv_[r].empty() || !contact_send_[r].empty() ||
        !contact_recv_[r].empty())
      out.push_back(r);
  return out;
}

std::int64_t PdHalo::bytes_per_update() const {
  std::int64_t b = 0;
  for (std::size_t r = 0; r < bond_send_.size(); ++r)
    b += static_cast<std::int64_t>(sizeof(double) *
                                   (4 * bond_send_[r].size() + 3 * contact_send_[r].size()));
  return b;
}

}  // namespace ballista::pd
