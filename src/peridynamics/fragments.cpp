#include "peridynamics/fragments.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "core/point_fields.hpp"
#include "peridynamics/pd_fields.hpp"
#include "points/point_exchange.hpp"

namespace ballista::pd {

namespace {

Index find_root(std::vector<Index>& parent, Index p) {
  while (parent[p] != p) {
    parent[p] = parent[parent[p]];  // path halving
    p = parent[p];
  }
  return p;
}

}  // namespace

std::vector<Fragment> find_fragments(const BondFamily& bonds, const FieldStore& store, double damage_threshold,
                                     const std::uint8_t* skip) {
  const Index n = store.size();
  const double* damage = damage_threshold <= 1.0 ? store.real(kBondDamage) : nullptr;
  auto kept = [&](Index p) { return !(skip && skip[p]) && (!damage || damage[p] <= damage_threshold); };
  std::vector<Index> parent(static_cast<size_t>(n));
  std::iota(parent.begin(), parent.end(), Index{0});
  for (Index p = 0; p < n; ++p)
    for (Index k = bonds.offset[p]; k < bonds.offset[p + 1]; ++k) {
      if (bonds.broken[k]) continue;
      const Index q = bonds.other[k];
      if (!kept(p) || !kept(q)) continue;
      Index a = find_root(parent, p), b = find_root(parent, q);
      if (a == b) continue;
      if (b < a) std::swap(a, b);
      parent[b] = a;  // the root is the lowest index: labels do not depend on the visiting order
    }
  const auto* x = store.view(kPosition);
  const auto* v = store.view(kVelocity);
  const auto* mass = store.real(kMass);
  std::vector<Index> slot(static_cast<size_t>(n), -1);
  std::vector<Fragment> out;
  for (Index p = 0; p < n; ++p) {
    if (!kept(p)) continue;
    const Index r = find_root(parent, p);
    if (slot[r] < 0) {
      slot[r] = static_cast<Index>(out.size());
      out.push_back({});
      out.back().first_point = r;
    }
    Fragment& f = out[slot[r]];
    f.points += 1;
    f.mass += mass[p];
    f.center += mass[p] * x[p];
    f.velocity += mass[p] * v[p];
  }
  for (Fragment& f : out) {
    f.center = (1.0 / f.mass) * f.center;
    f.velocity = (1.0 / f.mass) * f.velocity;
    f.kinetic_energy = 0.5 * f.mass * dot(f.velocity, f.velocity);
  }
  std::sort(out.begin(), out.end(), [](const Fragment& a, const Fragment& b) {
    return a.mass != b.mass ? a.mass > b.mass : a.first_point < b.first_point;
  });
  return out;
}

std::vector<Fragment> find_fragments_gathered(const Communicator& comm, const BondFamily& bonds,
                                              const std::vector<Index>& own, const std::int64_t* ids,
                                              const FieldStore& store, double damage_threshold,
                                              const std::vector<std::uint8_t>& skip_material) {
  // Each own point: its id, then the ids of its intact bonds' higher-id ends (count first).
  std::vector<std::int64_t> mine;
  for (Index l : own) {
    mine.push_back(ids[l]);
    const std::size_t at = mine.size();
    mine.push_back(0);
    for (Index k = bonds.offset[l]; k < bonds.offset[l + 1]; ++k)
      if (!bonds.broken[k] && ids[bonds.other[k]] > ids[l]) mine.push_back(ids[bonds.other[k]]);
    mine[at] = static_cast<std::int64_t>(mine.size() - at - 1);
  }
  std::vector<char> bytes(mine.size() * sizeof(std::int64_t));
  if (!bytes.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
  const std::vector<std::vector<char>> got = comm.gather(bytes, 0);
  const FieldStore all = gather_points(comm, store, 0, true);
  if (comm.rank() != 0) return {};
  // The union of the intact bonds over the points in id order: union-find labels and sums do not
  // depend on the order the bonds arrive in (fragments.cpp above), so this is the serial answer.
  const Index n = all.size();
  const auto* id = all.ints(kId);
  auto index_of = [&](std::int64_t i) { return static_cast<Index>(std::lower_bound(id, id + n, i) - id); };
  std::vector<std::pair<Index, Index>> edges;
  for (const auto& b : got) {
    std::vector<std::int64_t> v(b.size() / sizeof(std::int64_t));
    if (!v.empty()) std::memcpy(v.data(), b.data(), b.size());
    for (std::size_t at = 0; at < v.size();) {
      const Index p = index_of(v[at]);
      const auto c = static_cast<std::size_t>(v[at + 1]);
      for (std::size_t j = 0; j < c; ++j) edges.emplace_back(p, index_of(v[at + 2 + j]));
      at += 2 + c;
    }
  }
  BondFamily f;
  f.offset.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& e : edges) ++f.offset[e.first + 1];
  for (Index p = 0; p < n; ++p) f.offset[p + 1] += f.offset[p];
  f.other.resize(edges.size());
  f.broken.assign(edges.size(), 0);
  std::vector<Index> fill(f.offset.begin(), f.offset.end() - 1);
  for (const auto& e : edges) f.other[fill[e.first]++] = static_cast<std::int32_t>(e.second);
  std::vector<std::uint8_t> skip(static_cast<std::size_t>(n), 0);
  const auto* mat = all.ints(kMaterialIndex);
  bool any = false;
  for (Index p = 0; p < n; ++p) {
    skip[p] = mat[p] >= 0 && mat[p] < static_cast<std::int64_t>(skip_material.size()) && skip_material[mat[p]];
    any = any || skip[p];
  }
  return find_fragments(f, all, damage_threshold, any ? skip.data() : nullptr);
}

}  // namespace ballista::pd
