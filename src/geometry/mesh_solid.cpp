#include "geometry/mesh_solid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ballista {

std::array<std::array<int, 4>, 6> hex_tets(const std::array<int, 8>& h) {
  // Nodes 0-3 the bottom face, 4-7 the top face above them (Exodus HEX8). The six tetrahedra
  // about the diagonal 0-6, each a right-handed (positive) one for a right-handed hexahedron.
  return {{{h[0], h[1], h[2], h[6]},
           {h[0], h[2], h[3], h[6]},
           {h[0], h[3], h[7], h[6]},
           {h[0], h[7], h[4], h[6]},
           {h[0], h[4], h[5], h[6]},
           {h[0], h[5], h[1], h[6]}}};
}

double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

MeshSolid::MeshSolid(TetMesh mesh) : m_(std::move(mesh)) {
  const double inf = std::numeric_limits<double>::infinity();
  lower_ = {inf, inf, inf};
  upper_ = {-inf, -inf, -inf};
  for (const auto& t : m_.tets)
    for (int c = 0; c < 4; ++c)
      for (int d = 0; d < 3; ++d) {
        lower_[d] = std::min(lower_[d], m_.vertices[t[c]][d]);
        upper_[d] = std::max(upper_[d], m_.vertices[t[c]][d]);
      }
  const std::size_t nt = m_.tets.size();
  inverse_.resize(nt);
  for (std::size_t k = 0; k < nt; ++k) {
    const auto& t = m_.tets[k];
    const Vec3& a = m_.vertices[t[0]];
    Mat3 e;  // columns: the edges from vertex 0
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) e(d, c) = m_.vertices[t[c + 1]][d] - a[d];
    inverse_[k] = inverse(e);
    volume_ += tet_volume(a, m_.vertices[t[1]], m_.vertices[t[2]], m_.vertices[t[3]]);
  }
  // A uniform grid of about one tetrahedron per bin.
  const double side = std::cbrt(std::max(1.0, static_cast<double>(nt)));
  double extent[3];
  for (int d = 0; d < 3; ++d) extent[d] = std::max(upper_[d] - lower_[d], 1e-300);
  const double longest = std::max({extent[0], extent[1], extent[2]});
  for (int d = 0; d < 3; ++d) {
    n_[d] = std::clamp(static_cast<int>(std::ceil(side * extent[d] / longest)), 1, 256);
    d_[d] = extent[d] / n_[d];
  }
  auto bin = [&](double x, int d) {
    return std::clamp(static_cast<int>(std::floor((x - lower_[d]) / d_[d])), 0, n_[d] - 1);
  };
  std::vector<std::array<int, 6>> range(nt);
  std::vector<std::int32_t> count(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
  for (std::size_t k = 0; k < nt; ++k) {
    auto& r = range[k];
    for (int d = 0; d < 3; ++d) {
      double lo = inf, hi = -inf;
      for (int c = 0; c < 4; ++c) {
        lo = std::min(lo, m_.vertices[m_.tets[k][c]][d]);
        hi = std::max(hi, m_.vertices[m_.tets[k][c]][d]);
      }
      const double pad = 1e-9 * extent[d];  // a point on a bin's face finds the tetrahedra on both sides
      r[2 * d] = bin(lo - pad, d);
      r[2 * d + 1] = bin(hi + pad, d);
    }
    for (int i = r[0]; i <= r[1]; ++i)
      for (int j = r[2]; j <= r[3]; ++j)
        for (int l = r[4]; l <= r[5]; ++l) ++count[(static_cast<std::size_t>(i) * n_[1] + j) * n_[2] + l + 1];
  }
  for (std::size_t b = 1; b < count.size(); ++b) count[b] += count[b - 1];
  start_ = count;
  tets_.resize(static_cast<std::size_t>(start_.back()));
  std::vector<std::int32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t k = 0; k < nt; ++k) {
    const auto& r = range[k];
    for (int i = r[0]; i <= r[1]; ++i)
      for (int j = r[2]; j <= r[3]; ++j)
        for (int l = r[4]; l <= r[5]; ++l)
          tets_[static_cast<std::size_t>(fill[(static_cast<std::size_t>(i) * n_[1] + j) * n_[2] + l]++)] =
              static_cast<std::int32_t>(k);
  }
}

bool MeshSolid::contains(const Vec3& x) const {
  for (int d = 0; d < 3; ++d) {
    const double pad = 1e-12 * (upper_[d] - lower_[d]);
    if (x[d] < lower_[d] - pad || x[d] > upper_[d] + pad) return false;
  }
  int b[3];
  for (int d = 0; d < 3; ++d)
    b[d] = std::clamp(static_cast<int>(std::floor((x[d] - lower_[d]) / d_[d])), 0, n_[d] - 1);
  const std::size_t cell = (static_cast<std::size_t>(b[0]) * n_[1] + b[1]) * n_[2] + b[2];
  for (std::int32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
    const std::int32_t t = tets_[static_cast<std::size_t>(k)];
    const Vec3 r = x - m_.vertices[m_.tets[static_cast<std::size_t>(t)][0]];
    const Mat3& m = inverse_[static_cast<std::size_t>(t)];
    double sum = 0.0;
    bool in = true;
    for (int c = 0; c < 3 && in; ++c) {
      const double l = m(c, 0) * r[0] + m(c, 1) * r[1] + m(c, 2) * r[2];
      in = l >= -kTol;
      sum += l;
    }
    if (in && sum <= 1.0 + kTol) return true;
  }
  return false;
}

}  // namespace ballista
