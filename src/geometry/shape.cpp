#include "geometry/shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "geometry/revolution.hpp"

namespace ballista {

namespace {
// Coordinates of x relative to a cylinder's base centre: axial distance and radial distance.
void axial_radial(const ShapeSpec& s, const Vec3& x, int dim, double& axial, double& radial) {
  const Vec3 d = x - s.center;
  const int a = s.axis;
  if (dim == 2 && a == 2) {  // disk in the x-y plane
    axial = 0.0;
    radial = std::hypot(d[0], d[1]);
    return;
  }
  if (dim == 2) {  // axial section (plane strain) or r-z half plane (axisymmetric, centre x = 0)
    axial = d[a];
    radial = std::abs(d[1 - a]);
    return;
  }
  axial = d[a];
  double r2 = 0.0;
  for (int k = 0; k < 3; ++k)
    if (k != a) r2 += d[k] * d[k];
  radial = std::sqrt(r2);
}
bool is_revolution(const ShapeSpec& s) { return s.type == "cone" || s.type == "liner" || s.type == "revolution"; }

/// A solid of revolution's size for the closedness tolerance: its largest radius or length.
double outline_size(const ShapeSpec& s) {
  double r, a0, a1;
  outline_extent(s.outline, r, a0, a1);
  return std::max(r, a1 - a0);
}
}  // namespace

bool shape_contains(const ShapeSpec& s, const Vec3& x, int dim) {
  // Closed shapes with a tolerance of 1e-12 of their size: a lattice point that lies on a face in
  // exact arithmetic is inside whatever the round-off of its coordinates (an optimised and a
  // sanitizer build computed such points on either side of the face).
  constexpr double kTol = 1e-12;
  const int nd = dim == 3 ? 3 : 2;
  if (s.type == "box") {
    for (int k = 0; k < nd; ++k) {
      const double tol = kTol * (s.upper[k] - s.lower[k]);
      if (x[k] < s.lower[k] - tol || x[k] > s.upper[k] + tol) return false;
    }
    return true;
  }
  if (s.type == "sphere") {
    double r2 = 0.0;
    for (int k = 0; k < nd; ++k) r2 += (x[k] - s.center[k]) * (x[k] - s.center[k]);
    return r2 <= s.radius * s.radius * (1.0 + 2.0 * kTol);
  }
  if (s.type == "cylinder" || s.type == "tube") {
    double axial, radial;
    axial_radial(s, x, dim, axial, radial);
    const double tl = kTol * s.length, tr = kTol * s.radius;
    const bool in_length = (dim == 2 && s.axis == 2) || (axial >= -tl && axial <= s.length + tl);
    const double rin = s.type == "tube" ? s.inner_radius : -1.0;
    return in_length && radial <= s.radius + tr && radial >= rin - tr;
  }
  if (is_revolution(s)) {
    double axial, radial;
    axial_radial(s, x, dim, axial, radial);
    return outline_depth(s.outline, radial, axial) >= -kTol * outline_size(s);
  }
  if (s.type == "surface" || s.type == "mesh") return s.solid && s.solid->contains(x);  // 3D only (the deck reader)
  throw Error("unknown shape type '" + s.type + "'");
}

double shape_depth(const ShapeSpec& s, const Vec3& x, int dim) {
  const int nd = dim == 3 ? 3 : 2;
  if (s.type == "box") {
    double depth = std::numeric_limits<double>::infinity();
    for (int k = 0; k < nd; ++k) depth = std::min({depth, x[k] - s.lower[k], s.upper[k] - x[k]});
    return depth;
  }
  if (s.type == "sphere") {
    double r2 = 0.0;
    for (int k = 0; k < nd; ++k) r2 += (x[k] - s.center[k]) * (x[k] - s.center[k]);
    return s.radius - std::sqrt(r2);
  }
  if (s.type == "cylinder" || s.type == "tube") {
    double axial, radial;
    axial_radial(s, x, dim, axial, radial);
    double depth = s.radius - radial;
    if (!(dim == 2 && s.axis == 2)) depth = std::min({depth, axial, s.length - axial});
    if (s.type == "tube") depth = std::min(depth, radial - s.inner_radius);
    return depth;
  }
  if (is_revolution(s)) {
    double axial, radial;
    axial_radial(s, x, dim, axial, radial);
    return outline_depth(s.outline, radial, axial);
  }
  if (s.type == "surface" || s.type == "mesh")
    throw Error("shape_depth: not defined for a " + s.type + " shape (no distance to it is kept; shape_contains_by)");
  throw Error("unknown shape type '" + s.type + "'");
}

bool shape_contains_by(const ShapeSpec& s, const Vec3& x, int dim, double margin) {
  if (!s.solid) return shape_depth(s, x, dim) > margin;
  const bool all = margin > 0.0;  // inside by margin: every probe in; within |margin|: any
  const double h = std::abs(margin);
  if (s.solid->contains(x) != all) return !all;
  for (int d = 0; d < 3; ++d)
    for (const double sign : {-1.0, 1.0}) {
      Vec3 p = x;
      p[d] += sign * h;
      if (s.solid->contains(p) != all) return !all;
    }
  return all;
}

void shape_bounds(const ShapeSpec& s, int dim, Vec3& lo, Vec3& hi) {
  if (s.type == "box" || s.type == "surface" || s.type == "mesh") {  // a solid's lower/upper: its bounding box
    lo = s.lower;
    hi = s.upper;
  } else if (s.type == "sphere") {
    for (int k = 0; k < 3; ++k) { lo[k] = s.center[k] - s.radius; hi[k] = s.center[k] + s.radius; }
  } else if (is_revolution(s)) {
    double r, a0, a1;
    outline_extent(s.outline, r, a0, a1);
    for (int k = 0; k < 3; ++k) {
      lo[k] = k == s.axis ? s.center[k] + a0 : s.center[k] - r;
      hi[k] = k == s.axis ? s.center[k] + a1 : s.center[k] + r;
    }
  } else {  // cylinder, tube
    for (int k = 0; k < 3; ++k) {
      if (k == s.axis) {
        lo[k] = s.center[k];
        hi[k] = s.center[k] + s.length;
      } else {
        lo[k] = s.center[k] - s.radius;
        hi[k] = s.center[k] + s.radius;
      }
    }
    // 2D with axis x or y: the axial section [c - R, c + R] across the axis (axisymmetric decks
    // have c.x = 0; seeding keeps only r > 0 there).
  }
  if (dim == 2) { lo[2] = 0.0; hi[2] = 0.0; }
}

}  // namespace ballista
