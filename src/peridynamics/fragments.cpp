#include "peridynamics/fragments.hpp"

#include <algorithm>
#include <numeric>

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
  const double* damage = damage_threshold <= 1.0 ? store.real("damage") : nullptr;
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
  const auto* x = store.view<Vec3>("x");
  const auto* v = store.view<Vec3>("v");
  const auto* mass = store.real("mass");
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

}  // namespace ballista::pd
