#include "geometry/revolution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ballista {

namespace {

constexpr double kPi = 3.14159265358979323846;

double cross(const OutlinePoint& o, const OutlinePoint& a, const OutlinePoint& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/// Distance from p to the segment ab.
double segment_distance(const OutlinePoint& p, const OutlinePoint& a, const OutlinePoint& b) {
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double len2 = ex * ex + ey * ey;
  double t = len2 > 0.0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p[0] - (a[0] + t * ex), p[1] - (a[1] + t * ey));
}

bool on_segment(const OutlinePoint& p, const OutlinePoint& a, const OutlinePoint& b) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= p[1] &&
         p[1] <= std::max(a[1], b[1]);
}

/// True if the closed segments ab and cd share a point.
bool segments_meet(const OutlinePoint& a, const OutlinePoint& b, const OutlinePoint& c, const OutlinePoint& d) {
  const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_segment(a, c, d)) || (d2 == 0 && on_segment(b, c, d)) || (d3 == 0 && on_segment(c, a, b)) ||
         (d4 == 0 && on_segment(d, a, b));
}

}  // namespace

Outline cone_outline(double base, double top, double length) {
  Outline o{{0.0, 0.0}};
  if (base > 0.0) o.push_back({base, 0.0});
  if (top > 0.0) o.push_back({top, length});
  o.push_back({0.0, length});
  return o;
}

Outline liner_outline(double angle_deg, double thickness, double diameter) {
  const double alpha = 0.5 * angle_deg * kPi / 180.0, R = 0.5 * diameter;
  const double H = R / std::tan(alpha);
  return {{0.0, 0.0}, {R, H}, {R - thickness / std::cos(alpha), H}, {0.0, thickness / std::sin(alpha)}};
}

std::optional<std::string> outline_problem(const Outline& o) {
  const size_t n = o.size();
  if (n < 3) return "expected at least 3 vertices [r, a], got " + std::to_string(n);
  for (size_t k = 0; k < n; ++k) {
    if (!std::isfinite(o[k][0]) || !std::isfinite(o[k][1]))
      return "vertex " + std::to_string(k) + " is not finite";
    if (o[k][0] < 0.0) return "vertex " + std::to_string(k) + " has a negative radius (r >= 0: the half plane)";
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      const OutlinePoint &a = o[i], &b = o[(i + 1) % n], &c = o[j], &d = o[(j + 1) % n];
      if (adjacent) {
        // Neighbours share one vertex; they must not fold back onto each other.
        const OutlinePoint& far_i = j == i + 1 ? a : b;
        const OutlinePoint& far_j = j == i + 1 ? d : c;
        const OutlinePoint& shared = j == i + 1 ? b : a;
        if (cross(shared, far_i, far_j) == 0.0 &&
            (far_i[0] - shared[0]) * (far_j[0] - shared[0]) + (far_i[1] - shared[1]) * (far_j[1] - shared[1]) > 0.0)
          return "edges " + std::to_string(i) + " and " + std::to_string(j) + " fold back onto each other";
        continue;
      }
      if (segments_meet(a, b, c, d))
        return "edges " + std::to_string(i) + " and " + std::to_string(j) +
               " cross or touch (the outline must be a simple polygon)";
    }
  double area = 0.0;
  outline_volume(o, &area);
  if (!(std::abs(area) > 0.0)) return "the outline encloses no area";
  return std::nullopt;
}

double outline_depth(const Outline& o, double r, double a) {
  const OutlinePoint p{r, a};
  const size_t n = o.size();
  double dist = std::numeric_limits<double>::infinity();
  bool inside = false;
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    dist = std::min(dist, segment_distance(p, o[j], o[i]));
    // Crossing number along +r.
    if ((o[i][1] > a) != (o[j][1] > a)) {
      const double rc = o[j][0] + (a - o[j][1]) * (o[i][0] - o[j][0]) / (o[i][1] - o[j][1]);
      if (r < rc) inside = !inside;
    }
  }
  return inside ? dist : -dist;
}

void outline_extent(const Outline& o, double& r_max, double& a_min, double& a_max) {
  r_max = 0.0;
  a_min = std::numeric_limits<double>::infinity();
  a_max = -a_min;
  for (const auto& v : o) {
    r_max = std::max(r_max, v[0]);
    a_min = std::min(a_min, v[1]);
    a_max = std::max(a_max, v[1]);
  }
}

double outline_volume(const Outline& o, double* area) {
  // Shoelace for the area and the first moment about the axis (r = 0).
  double A = 0.0, Mr = 0.0;
  const size_t n = o.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const double c = o[j][0] * o[i][1] - o[i][0] * o[j][1];
    A += c;
    Mr += (o[j][0] + o[i][0]) * c;
  }
  A *= 0.5;
  Mr /= 6.0;
  if (area) *area = std::abs(A);
  return 2.0 * kPi * std::abs(Mr);
}

}  // namespace ballista
