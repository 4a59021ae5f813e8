#pragma once
// The lattice with its surface cells cut to the shape (bodies[].seeding: cut_lattice).
//
// A lattice body keeps a sub-cell whole when its centre is inside the shape, so its surface is a
// staircase: a cylinder of radius R seeded at spacing d reaches up to ~d/2 beyond R along the
// lattice's diagonals and its mass is off by O(d/R) (the 3D OTM Taylor bar: +3.5 % at 0.8 mm cells).
// Here a sub-cell the surface cuts keeps only its part inside the shape: the point takes that part's
// volume and sits at its centroid, so the seeded volume and its first moment are the shape's to the
// sampling error: the part inside is integrated on boxes of 1/8 of the sub-cell, those the surface
// crosses sampled finer (kCutSamples below). This is
// the volume-fraction initialisation of Eulerian and cut-cell methods applied to one point per
// sub-cell.
//
// A sliver (less than half of its sub-cell inside) would make a point far lighter than the rest,
// and the solvers' thresholds relative to the lightest point (OTM's light nodes) and their stable
// steps would follow it; so a sliver's volume and first moment go to the nearest kept point among
// its 26 neighbours (volume and centroid stay exact), and only a sliver with no kept neighbour
// becomes a point of its own.
//
// Cells are found cut where their centre's inside/outside differs from one of their 26
// neighbours': a feature thinner than a sub-cell may be missed, as on the plain lattice.
#include <array>
#include <functional>
#include <vector>

#include "core/tensor.hpp"

namespace ballista {

/// One point of the cut lattice.
struct CutLatticePoint {
  Vec3 at;         ///< m: the sub-cell's centre when whole, else the centroid of its part inside
  double measure;  ///< the volume (3D), area (2D) or r-weighted area (axisymmetric: volume per radian)
  Vec3 half;       ///< m: half the sub-cell's size, scaled by (its volume or area / the whole sub-cell's)^(1/dim)
};

/// The lattice's sites along each axis (sub-cell centres, increasing) and their spacings; axes
/// beyond `dim` hold one site at 0 with spacing 0.
struct LatticeSites {
  std::array<std::vector<double>, 3> at, spacing;
};

/// Boxes per axis a cut sub-cell is divided into; those the surface crosses are sampled at
/// cut_refinement(dim) points per axis, so the surface is resolved to
/// d / (kCutSamples cut_refinement(dim)): 1/32 of the spacing in 3D, 1/128 in 2D. A face lying
/// along the lattice is thus off by at most half that (its area times d/64 in 3D: 0.05 % of a plate
/// 32 spacings thick); a curved one's errors are of both signs and cancel over its area.
inline constexpr int kCutSamples = 8;
inline constexpr int cut_refinement(int dim) { return dim == 3 ? 4 : 16; }

/// The points of the cut lattice over `sites` for the region `inside` (shape, cutouts and grid box
/// together); `axisymmetric` weights by r = x (and requires x > 0). Ordered like the plain lattice
/// (x fastest, then y, then z). Whole sub-cells give exactly the plain lattice's point.
std::vector<CutLatticePoint> cut_lattice_points(const LatticeSites& sites, int dim, bool axisymmetric,
                                                const std::function<bool(const Vec3&)>& inside);

}  // namespace ballista
