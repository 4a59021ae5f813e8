#pragma once
// Solid shapes used to seed bodies: point-membership tests and bounding boxes.
#include "core/tensor.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// True if point x lies inside the shape. In 2D (dim == 2) only x[0], x[1] are used:
/// a cylinder/tube with axis z is a disk/annulus; with axis y (axisymmetric) it is the
/// rectangle 0 <= r <= radius, center.y <= y <= center.y + length in the (r, z) half plane.
bool shape_contains(const ShapeSpec& s, const Vec3& x, int dim);

/// How deep x lies inside the shape: the distance to its nearest face if inside (> 0), a
/// negative number if outside (its size is not a distance then). Same 2D conventions as
/// shape_contains. For overlap checks that must not count a point lying on a shared face.
double shape_depth(const ShapeSpec& s, const Vec3& x, int dim);

/// x lies inside the shape by more than `margin` (a negative margin: inside, or outside by less
/// than |margin|). For the analytic shapes shape_depth(x) > margin; a surface or mesh solid keeps
/// no distance, so x and the six points x +- |margin| along the axes are probed: inside by more
/// than margin when all seven are inside, within |margin| of it when any is.
bool shape_contains_by(const ShapeSpec& s, const Vec3& x, int dim, double margin);

/// Axis-aligned bounding box of the shape (2D: z components are 0).
void shape_bounds(const ShapeSpec& s, int dim, Vec3& lower, Vec3& upper);

}  // namespace ballista
