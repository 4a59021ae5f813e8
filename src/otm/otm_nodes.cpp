#include "otm/otm_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace ballista::otm {

NodeCloud seed_nodes(const Vec3* x, const std::int64_t* body, Index n, const Vec3& lower, double h, int dim) {
  // Every vertex (i, j, k) of a point's cell, per body; sorted and made unique.
  std::vector<std::tuple<std::int64_t, long, long, long>> keys;
  keys.reserve(static_cast<size_t>(n) * (dim == 3 ? 8 : 4));
  for (Index p = 0; p < n; ++p) {
    long c[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) c[a] = static_cast<long>(std::floor((x[p][a] - lower[a]) / h));
    const int kz = dim == 3 ? 1 : 0;
    for (int dz = 0; dz <= kz; ++dz)
      for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) keys.emplace_back(body[p], c[2] + dz, c[1] + dy, c[0] + dx);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  NodeCloud nodes;
  nodes.x.reserve(keys.size());
  for (const auto& [b, k, j, i] : keys) {
    nodes.x.push_back(Vec3{{lower[0] + static_cast<double>(i) * h, lower[1] + static_cast<double>(j) * h,
                            dim == 3 ? lower[2] + static_cast<double>(k) * h : 0.0}});
    nodes.body.push_back(b);
  }
  nodes.v.assign(nodes.x.size(), Vec3{});
  nodes.f.assign(nodes.x.size(), Vec3{});
  nodes.mass.assign(nodes.x.size(), 0.0);
  return nodes;
}

}  // namespace ballista::otm
