#pragma once
// The solid bounded by a triangle surface (a body's `shape: {type: surface}`), for seeding: is a
// lattice point inside? A ray from the point crosses a closed surface an odd number of times iff
// the point is inside (Jordan). Three rays, along x, y and z, vote: a surface with a small hole
// (a CAD export with a missing facet) misleads only the rays that pass through the hole, so the
// majority stays right where a single ray would flip a whole row of points.
#include <array>
#include <cstdint>
#include <vector>

#include "core/tensor.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

struct TriangleSurface {
  std::vector<Vec3> vertices;                 ///< m
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices (shared vertices welded)
};

/// How well a surface closes: an edge of a closed surface borders exactly two triangles.
struct SurfaceClosure {
  std::int64_t edges = 0;
  std::int64_t open_edges = 0;         ///< bordering one triangle only (a hole's rim)
  std::int64_t non_manifold_edges = 0;  ///< bordering three or more
  Vec3 open_edge_at{};                 ///< the midpoint of one open edge (for the message)
};
SurfaceClosure surface_closure(const TriangleSurface& s);

class SurfaceSolid final : public SolidShape {
 public:
  explicit SurfaceSolid(TriangleSurface surface);
  bool contains(const Vec3& x) const override;
  Vec3 lower() const override { return lower_; }
  Vec3 upper() const override { return upper_; }

 private:
  /// The triangles whose projection across `axis` may hold a point, binned on a uniform grid
  /// over the other two coordinates.
  struct AxisBins {
    int axis = 0, u = 1, v = 2;  ///< ray direction and the two transverse coordinates
    int nu = 1, nv = 1;
    double u0 = 0, v0 = 0, du = 1, dv = 1;
    std::vector<std::int32_t> start;  ///< CSR offsets, nu * nv + 1
    std::vector<std::int32_t> tris;
  };
  void build_bins(int axis, AxisBins& b) const;
  /// Parity of the crossings of the ray from x along +axis (true: odd, inside).
  bool ray_parity(const AxisBins& b, const Vec3& x) const;

  TriangleSurface s_;
  Vec3 lower_, upper_;
  double jitter_;  ///< transverse offset of the rays: no ray passes exactly through an edge
  std::array<AxisBins, 3> bins_;
};

}  // namespace ballista
