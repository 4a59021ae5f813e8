#pragma once
// The solid filled by a volume mesh (a body's `shape: {type: mesh}`, an Exodus II file read by the
// deck reader), for seeding: is a lattice point inside one of its elements? The mesh only says
// where the material is; the body is seeded with its own lattice like any other shape. Hexahedra
// are split into six tetrahedra about their 0-6 diagonal (exact for hexahedra with planar faces;
// a warped face is taken as two triangles, a gap or overlap of the order of its warp).
#include <array>
#include <cstdint>
#include <vector>

#include "core/tensor.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

struct TetMesh {
  std::vector<Vec3> vertices;               ///< m
  std::vector<std::array<int, 4>> tets;     ///< vertex indices, positive volume
};

/// The six tetrahedra of an 8-node hexahedron in Exodus (and VTK) node order (nodes 0-3 one face,
/// counter-clockwise about the direction into the element; 4-7 the opposite face, node 4 across
/// from node 0), all six about the diagonal 0-6 and positive for a positive hexahedron.
std::array<std::array<int, 4>, 6> hex_tets(const std::array<int, 8>& h);

/// Signed volume of the tetrahedron (a, b, c, d): positive when (b-a, c-a, d-a) is right-handed.
double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

class MeshSolid final : public SolidShape {
 public:
  explicit MeshSolid(TetMesh mesh);
  bool contains(const Vec3& x) const override;
  Vec3 lower() const override { return lower_; }
  Vec3 upper() const override { return upper_; }
  /// Total volume of the tetrahedra, m^3.
  double volume() const { return volume_; }
  /// The tetrahedra and their vertices (bodies seeded at the elements; OTM's nodes on them).
  const TetMesh& mesh() const { return m_; }

 private:
  TetMesh m_;
  Vec3 lower_, upper_;
  double volume_ = 0.0;
  /// Barycentric tolerance: like the analytic shapes (geometry/shape.cpp), a lattice point on a
  /// face is inside whatever its round-off, so a mesh of a box seeds the box's points.
  static constexpr double kTol = 1e-12;
  int n_[3] = {1, 1, 1};
  double d_[3] = {1, 1, 1};
  std::vector<std::int32_t> start_;  ///< CSR offsets per bin of a uniform 3D grid over the box
  std::vector<std::int32_t> tets_;
  /// The tetrahedra whose box overlaps a bin; and each tetrahedron's inverse map to barycentric
  /// coordinates (rows: lambda_1..3 = M (x - v0)).
  std::vector<Mat3> inverse_;
};

}  // namespace ballista
