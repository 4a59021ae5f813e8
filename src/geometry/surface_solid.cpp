#include "geometry/surface_solid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace ballista {

SurfaceClosure surface_closure(const TriangleSurface& s) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  SurfaceClosure c;
  c.edges = static_cast<std::int64_t>(uses.size());
  for (const auto& [edge, n] : uses) {
    if (n == 1 && c.open_edges++ == 0)
      c.open_edge_at = 0.5 * (s.vertices[edge.first] + s.vertices[edge.second]);
    if (n > 2) ++c.non_manifold_edges;
  }
  return c;
}

SurfaceSolid::SurfaceSolid(TriangleSurface surface) : s_(std::move(surface)) {
  const double inf = std::numeric_limits<double>::infinity();
  lower_ = {inf, inf, inf};
  upper_ = {-inf, -inf, -inf};
  for (const Vec3& p : s_.vertices)
    for (int d = 0; d < 3; ++d) {
      lower_[d] = std::min(lower_[d], p[d]);
      upper_[d] = std::max(upper_[d], p[d]);
    }
  double size = 0.0;
  for (int d = 0; d < 3; ++d) size = std::max(size, upper_[d] - lower_[d]);
  // Far below any lattice spacing, far above round-off: a lattice point on a CAD face's edge line
  // (x = a grid line = the edge's coordinate) is then on one side of the edge, not on it.
  jitter_ = 1e-9 * size;
  for (int a = 0; a < 3; ++a) build_bins(a, bins_[a]);
}

void SurfaceSolid::build_bins(int axis, AxisBins& b) const {
  b.axis = axis;
  b.u = (axis + 1) % 3;
  b.v = (axis + 2) % 3;
  const std::size_t nt = s_.triangles.size();
  // About two triangles per bin along the side of a square grid.
  const int side = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(nt) / 2.0)), 1, 512);
  b.nu = b.nv = side;
  b.u0 = lower_[b.u];
  b.v0 = lower_[b.v];
  b.du = std::max(upper_[b.u] - lower_[b.u], 1e-300) / side;
  b.dv = std::max(upper_[b.v] - lower_[b.v], 1e-300) / side;
  auto cell = [&](double x, double x0, double dx, int n) {
    return std::clamp(static_cast<int>(std::floor((x - x0) / dx)), 0, n - 1);
  };
  std::vector<std::array<int, 4>> range(nt);  // u0, u1, v0, v1 bins of each triangle
  std::vector<std::int32_t> count(static_cast<std::size_t>(side) * side + 1, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    double ulo = 1e300, uhi = -1e300, vlo = 1e300, vhi = -1e300;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = s_.vertices[s_.triangles[t][k]];
      ulo = std::min(ulo, p[b.u]);
      uhi = std::max(uhi, p[b.u]);
      vlo = std::min(vlo, p[b.v]);
      vhi = std::max(vhi, p[b.v]);
    }
    // Widened by the jitter: a ray shifted by it still finds the triangle in its bin.
    range[t] = {cell(ulo - 2 * jitter_, b.u0, b.du, side), cell(uhi + 2 * jitter_, b.u0, b.du, side),
                cell(vlo - 2 * jitter_, b.v0, b.dv, side), cell(vhi + 2 * jitter_, b.v0, b.dv, side)};
    for (int i = range[t][0]; i <= range[t][1]; ++i)
      for (int j = range[t][2]; j <= range[t][3]; ++j) ++count[static_cast<std::size_t>(i) * side + j + 1];
  }
  for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
  b.start = count;
  b.tris.resize(static_cast<std::size_t>(count.back()));
  std::vector<std::int32_t> fill(count.begin(), count.end() - 1);
  for (std::size_t t = 0; t < nt; ++t)
    for (int i = range[t][0]; i <= range[t][1]; ++i)
      for (int j = range[t][2]; j <= range[t][3]; ++j)
        b.tris[static_cast<std::size_t>(fill[static_cast<std::size_t>(i) * side + j]++)] = static_cast<std::int32_t>(t);
}

bool SurfaceSolid::ray_parity(const AxisBins& b, const Vec3& x) const {
  // The ray's transverse position, shifted by unequal multiples of the jitter.
  const double pu = x[b.u] + jitter_ * (0.5 + 0.13 * b.axis), pv = x[b.v] + jitter_ * (0.31 + 0.07 * b.axis);
  if (pu < b.u0 || pv < b.v0 || pu > b.u0 + b.nu * b.du || pv > b.v0 + b.nv * b.dv) return false;
  const int i = std::clamp(static_cast<int>((pu - b.u0) / b.du), 0, b.nu - 1);
  const int j = std::clamp(static_cast<int>((pv - b.v0) / b.dv), 0, b.nv - 1);
  const std::size_t k = static_cast<std::size_t>(i) * b.nv + j;
  bool odd = false;
  for (std::int32_t n = b.start[k]; n < b.start[k + 1]; ++n) {
    const auto& t = s_.triangles[static_cast<std::size_t>(b.tris[static_cast<std::size_t>(n)])];
    const Vec3 &p0 = s_.vertices[t[0]], &p1 = s_.vertices[t[1]], &p2 = s_.vertices[t[2]];
    // Signed areas of the sub-triangles in the (u, v) projection: the ray meets the triangle iff
    // they share a sign (either orientation of the triangle).
    auto edge = [&](const Vec3& a, const Vec3& c) {
      return (a[b.u] - pu) * (c[b.v] - pv) - (a[b.v] - pv) * (c[b.u] - pu);
    };
    const double w0 = edge(p1, p2), w1 = edge(p2, p0), w2 = edge(p0, p1);
    const bool pos = w0 > 0 && w1 > 0 && w2 > 0, neg = w0 < 0 && w1 < 0 && w2 < 0;
    if (!pos && !neg) continue;
    // The crossing's coordinate along the ray, by the barycentric weights.
    const double hit = (w0 * p0[b.axis] + w1 * p1[b.axis] + w2 * p2[b.axis]) / (w0 + w1 + w2);
    if (hit > x[b.axis]) odd = !odd;
  }
  return odd;
}

bool SurfaceSolid::contains(const Vec3& x) const {
  for (int d = 0; d < 3; ++d)
    if (x[d] < lower_[d] || x[d] > upper_[d]) return false;
  const int votes = int(ray_parity(bins_[0], x)) + int(ray_parity(bins_[1], x)) + int(ray_parity(bins_[2], x));
  return votes >= 2;
}

}  // namespace ballista
