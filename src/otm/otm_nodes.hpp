#pragma once
// The nodes of the OTM discretisation (seed 003 ch. 2.2, Fig. 2-1): they carry the motion, the
// material points carry the material. Seeded per body at the vertices of every lattice cell
// (spacing grid.cell_size, aligned with grid.lower) that holds one of the body's points, so every
// point lies inside the convex hull of the nodes around it (the LME solve needs that) and the
// nodes of different bodies are distinct (bodies do not share a velocity field).
#include <cstdint>
#include <vector>

#include "core/field_store.hpp"
#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "scenario/scenario.hpp"

namespace ballista::otm {

struct NodeCloud {
  std::vector<Vec3> x;       ///< m, current position
  std::vector<Vec3> v;       ///< m/s, velocity of the last step (x_k - x_{k-1}) / dt_k (seed 003 eq. 2.14)
  std::vector<Vec3> f;       ///< N, residual force of the current step
  std::vector<double> mass;  ///< kg, lumped (seed 003 eq. 2.13); per radian in axisymmetric runs
  std::vector<std::int64_t> body;  ///< body index
  Index size() const { return static_cast<Index>(x.size()); }
};

/// Nodes at the vertices of the cells (size h, aligned with `lower`) holding points of each body;
/// nodes of one body are ordered by cell vertex index (deterministic). z ignored when dim == 2.
NodeCloud seed_nodes(const Vec3* x, const std::int64_t* body, Index n, const Vec3& lower, double h, int dim);

}  // namespace ballista::otm
