#include "points/body_overlap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/error.hpp"
#include "core/point_fields.hpp"
#include "geometry/seeding.hpp"
#include "geometry/shape.hpp"

namespace ballista {

namespace {

/// The space a body claims: its shape (or its segments' shapes) less its cutouts.
struct Region {
  std::vector<ShapeSpec> parts;
  std::vector<ShapeSpec> cutouts;
  Vec3 lower, upper;  ///< bounding box of the parts
};

Region region_of(const BodySpec& b, int nd) {
  Region r;
  if (b.segments.empty()) {
    r.parts.push_back(b.shape);
  } else {
    for (const SegmentSpec& s : b.segments) r.parts.push_back(s.shape);
  }
  r.cutouts = b.cutouts;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  r.lower = Vec3{{kInf, kInf, kInf}};
  r.upper = Vec3{{-kInf, -kInf, -kInf}};
  for (const ShapeSpec& s : r.parts) {
    Vec3 lo, hi;
    shape_bounds(s, nd, lo, hi);
    for (int k = 0; k < 3; ++k) {
      r.lower[k] = std::min(r.lower[k], lo[k]);
      r.upper[k] = std::max(r.upper[k], hi[k]);
    }
  }
  return r;
}

/// x inside the region by more than `margin` (and outside every cutout by more than it).
bool inside(const Region& r, const Vec3& x, int nd, double margin) {
  for (int k = 0; k < nd; ++k)
    if (x[k] <= r.lower[k] + margin || x[k] >= r.upper[k] - margin) return false;
  bool in = false;
  for (const ShapeSpec& s : r.parts)
    if (shape_contains_by(s, x, nd, margin)) {
      in = true;
      break;
    }
  if (!in) return false;
  for (const ShapeSpec& c : r.cutouts)
    if (shape_contains_by(c, x, nd, -margin)) return false;
  return true;
}

struct Overlap {
  Index points = 0;
  double volume = 0.0;
  Vec3 lower, upper;
};

std::string where(const BodySpec& b) {
  return b.mark.key_path + (b.mark.line > 0 ? " at line " + std::to_string(b.mark.line) : std::string());
}

}  // namespace

void check_body_overlaps(const Scenario& sc, const FieldStore& points) {
  const std::size_t nb = sc.bodies.size();
  if (nb < 2) return;
  const int nd = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  // Axisymmetric volumes are per radian (geometry/seeding.hpp): the shared volume is 2 pi times.
  const double volume_scale = sc.simulation.dimension == Dimension::Axisymmetric ? 2.0 * std::numbers::pi : 1.0;
  std::vector<Region> regions;
  std::vector<double> margin;
  for (const BodySpec& b : sc.bodies) {
    regions.push_back(region_of(b, nd));
    margin.push_back(0.01 * seed_spacing(b, sc.grid.cell_size));
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<Overlap> found(nb * nb);
  for (Overlap& o : found) {
    o.lower = Vec3{{kInf, kInf, kInf}};
    o.upper = Vec3{{-kInf, -kInf, -kInf}};
  }
  const auto* x0 = points.view(kReferencePosition);
  const auto* body = points.ints(kBodyIndex);
  const auto* vol0 = points.real(kReferenceVolume);
  for (Index p = 0; p < points.size(); ++p) {
    const std::size_t a = static_cast<std::size_t>(body[p]);
    for (std::size_t b = 0; b < nb; ++b) {
      if (b == a || !inside(regions[b], x0[p], nd, margin[a])) continue;
      Overlap& o = found[a * nb + b];
      ++o.points;
      o.volume += volume_scale * vol0[p];
      for (int k = 0; k < 3; ++k) {
        o.lower[k] = std::min(o.lower[k], x0[p][k]);
        o.upper[k] = std::max(o.upper[k], x0[p][k]);
      }
    }
  }
  // Each unordered pair once, seen from the body with more points inside the other; the pair
  // sharing the most is named, the others counted.
  std::size_t worst = nb * nb, pairs = 0;
  for (std::size_t a = 0; a < nb; ++a)
    for (std::size_t b = a + 1; b < nb; ++b) {
      const std::size_t ab = a * nb + b, ba = b * nb + a;
      if (found[ab].points + found[ba].points == 0) continue;
      ++pairs;
      const std::size_t k = found[ab].points >= found[ba].points ? ab : ba;
      if (worst == nb * nb || found[k].points > found[worst].points) worst = k;
    }
  if (pairs == 0) return;
  const std::size_t a = worst / nb, b = worst % nb;
  const Overlap& o = found[worst];
  const BodySpec& later = sc.bodies[std::max(a, b)];
  static const char axes[3] = {'x', 'y', 'z'};
  std::string extent;
  for (int k = 0; k < nd; ++k)
    extent += fmt::format("{}{} {:.4g} to {:.4g} m", k ? ", " : "", axes[k], o.lower[k], o.upper[k]);
  throw DeckError(later.mark.file, later.mark.line, later.mark.column, later.mark.key_path,
                  fmt::format("bodies '{}' ({}) and '{}' ({}) overlap: {} points of '{}' lie inside '{}', about {:.3g} "
                              "m^3{} ({}){}; bodies may touch but not share space: move or shrink one, or cut the "
                              "other out of it with cutouts",
                              sc.bodies[a].name, where(sc.bodies[a]), sc.bodies[b].name, where(sc.bodies[b]), o.points,
                              sc.bodies[a].name, sc.bodies[b].name, o.volume,
                              nd == 2 && volume_scale == 1.0 ? " per metre of thickness" : "", extent,
                              pairs > 1 ? fmt::format("; {} more pairs of bodies overlap", pairs - 1) : std::string()));
}

}  // namespace ballista
