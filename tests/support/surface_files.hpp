#pragma once
// Closed triangle surfaces for the tests of surface shapes: a box and an icosphere, as triangle
// lists and as ASCII STL text.
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/tensor.hpp"

namespace ballista::test {

using Triangle = std::array<Vec3, 3>;

/// The 12 triangles of the box [lo, hi], wound outward.
inline std::vector<Triangle> box_triangles(const Vec3& lo, const Vec3& hi) {
  auto c = [&](int i, int j, int k) { return Vec3{{i ? hi[0] : lo[0], j ? hi[1] : lo[1], k ? hi[2] : lo[2]}}; };
  const int q[6][4][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                          {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
                          {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
  std::vector<Triangle> t;
  for (const auto& f : q) {
    const Vec3 a = c(f[0][0], f[0][1], f[0][2]), b = c(f[1][0], f[1][1], f[1][2]), d = c(f[2][0], f[2][1], f[2][2]),
               e = c(f[3][0], f[3][1], f[3][2]);
    t.push_back({a, b, d});
    t.push_back({a, d, e});
  }
  return t;
}

/// An icosahedron subdivided `levels` times and projected on the sphere (centre, radius): its
/// vertices lie on the sphere, so the solid lies inside the sphere and contains the sphere of
/// radius radius * cos(largest facet angle).
inline std::vector<Triangle> icosphere_triangles(const Vec3& centre, double radius, int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{{-1, g, 0}}, {{1, g, 0}},  {{-1, -g, 0}}, {{1, -g, 0}}, {{0, -1, g}}, {{0, 1, g}},
                         {{0, -1, -g}}, {{0, 1, -g}}, {{g, 0, -1}},  {{g, 0, 1}},   {{-g, 0, -1}}, {{-g, 0, 1}}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  auto unit = [](const Vec3& p) { return (1.0 / std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])) * p; };
  for (Vec3& p : v) p = unit(p);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      v.push_back(unit(0.5 * (v[a] + v[b])));
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : f) {
      const int a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c = midpoint(t[2], t[0]);
      next.insert(next.end(), {{t[0], a, c}, {t[1], b, a}, {t[2], c, b}, {a, b, c}});
    }
    f = std::move(next);
  }
  std::vector<Triangle> t;
  for (const auto& k : f) t.push_back({centre + radius * v[k[0]], centre + radius * v[k[1]], centre + radius * v[k[2]]});
  return t;
}

/// ASCII STL of the triangles, coordinates multiplied by `scale` (1000: a file in mm).
inline std::string stl_text(const std::vector<Triangle>& tris, double scale = 1.0) {
  std::ostringstream s;
  s.precision(17);
  s << "solid test\n";
  for (const auto& t : tris) {
    s << "  facet normal 0 0 0\n    outer loop\n";
    for (const Vec3& p : t) s << "      vertex " << scale * p[0] << " " << scale * p[1] << " " << scale * p[2] << "\n";
    s << "    endloop\n  endfacet\n";
  }
  s << "endsolid test\n";
  return s.str();
}

}  // namespace ballista::test
