#pragma once
// The corners of a point's deformed domain, x_p + F_p (+-a, +-b, +-c) with (a, b, c) = half_size:
// the probes measure a body's surface from them, not only from the point centres.
#include "core/field_store.hpp"
#include "core/point_fields.hpp"
#include "core/tensor.hpp"

namespace ballista {

/// Calls f(corner) for each corner of a point's deformed domain (4 in 2D, 8 in 3D).
template <class Fn>
void for_each_corner(const Vec3& x, const Mat3& F, const Vec3& half, int nd, Fn&& f) {
  const int ncorner = nd == 3 ? 8 : 4;
  for (int c = 0; c < ncorner; ++c) {
    const Vec3 s{{(c & 1 ? 1.0 : -1.0) * half[0], (c & 2 ? 1.0 : -1.0) * half[1],
                  nd == 3 ? (c & 4 ? 1.0 : -1.0) * half[2] : 0.0}};
    f(x + F * s);
  }
}

/// The three fields that place every point's deformed domain, looked up once per evaluation
/// rather than by each probe that walks the corners.
struct PointDomains {
  PointDomains(const FieldStore& points, int dims)
      : x(points.view(kPosition)), F(points.view(kDeformationGradient)), half(points.view(kHalfSize)), nd(dims) {}

  /// Calls f(corner) for each corner of point p's deformed domain.
  template <class Fn>
  void for_each_corner(Index p, Fn&& f) const {
    ballista::for_each_corner(x[p], F[p], half[p], nd, f);
  }

  const Vec3* x;
  const Mat3* F;
  const Vec3* half;
  int nd;
};

}  // namespace ballista
