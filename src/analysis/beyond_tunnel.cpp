#include "analysis/beyond_tunnel.hpp"

#include <algorithm>
#include <cstddef>

namespace ballista {

BeyondTunnel beyond_tunnel(const std::vector<double>& depth, const std::vector<double>& mass, double floor,
                           double margin) {
  BeyondTunnel b;
  double total = 0.0;
  for (std::size_t p = 0; p < depth.size(); ++p) {
    total += mass[p];
    if (!(depth[p] > floor + margin)) {
      b.deepest_within = std::max(b.deepest_within, depth[p]);
      continue;
    }
    ++b.points;
    b.mass += mass[p];
    b.deepest = std::max(b.deepest, depth[p]);
  }
  b.mass_share = total > 0.0 ? b.mass / total : 0.0;
  return b;
}

}  // namespace ballista
