#pragma once
// Adaptivity of the OTM discretisation (seed 003 ch. 5): material points split where the material
// has stretched them, and the nodes are re-generated on the lattice where they no longer resolve the
// material (too far from a point, or crowded together) — conditioning-aware node injection.
//
// Why not the seed's Algorithm 2 as it stands: its metric (a node's nearest-neighbour distance
// above tol) finds nothing under anisotropic stretch (a flattening Taylor foot keeps its nodes close
// along the axis while they spread radially), and its new nodes midway between existing ones give
// the ill-conditioned LME solves of seed Figs. 5-3 to 5-5 (tests/unit/otm/test_lme_shape.cpp
// reproduces the cube experiment). So:
//  * points (the seed's "identical metric for the points"): a point whose extent along some
//    direction has grown beyond split_stretch times its seeded spacing splits in two along that
//    direction (the direction-aware version of the distance metric). The children sit at the
//    centres of the two halves of the parent's cell, whose map is the parent's F (kept); their
//    material state is the parent's moved along the limited linear reconstruction of the
//    neighbourhood (split_state.hpp), or with otm.split_state: copy the parent's own; mass,
//    volume and energies are halved, so every extensive quantity is conserved exactly.
//  * nodes: when a point's nearest node is farther than node_gap h, two nodes of a body are closer
//    than node_crowding h, a point split, or an LME solve failed, the nodes are re-generated at the
//    vertices of the lattice cells that hold the points (exactly the initial seeding, otm_nodes.hpp):
//    every injected node is "moved" to a lattice vertex, so the LME problems stay those of a
//    regular lattice (condition numbers of the initial state) instead of the seed's midpoint nodes.
//    A new node's velocity is the old nodes' LME interpolant at its position (the nearest point's
//    velocity for a vertex outside the old nodes' hull); a uniform correction over each body's
//    free nodes then restores the linear momentum exactly, and the kinetic-energy change of the
//    re-generation is booked (summary.json transfer_work).
#include <cstdint>
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "otm/otm_nodes.hpp"
#include "otm/split_state.hpp"

namespace ballista::otm {

struct AdaptivityOptions {
  bool enabled = false;
  double split_stretch = 2.0;   ///< split a point whose extent exceeds this times its seeded spacing
  double node_gap = 1.0;        ///< regenerate when a point's nearest node is farther than this times h
  double node_crowding = 0.25;  ///< ... or two nodes of one body are closer than this times h
  double max_condition = 1e6;   ///< ... or a point's LME Hessian is worse conditioned than this
};

/// Name of the per-point extent tensor (m): the edges of the point's cell, s0 I at seeding,
/// carried as S <- dF S and halved along the split direction.
inline constexpr FieldKey<Mat3> kExtent{"extent"};
inline constexpr const char* kExtentField = kExtent.name();

/// Unit eigenvector of the largest eigenvalue `hi` of the symmetric dim x dim block of A.
Vec3 largest_eigenvector(const Mat3& A, int dim, double hi);

/// Splits every point whose extent (largest singular value of its extent tensor, in the plane in
/// 2D) exceeds opt.split_stretch times spacing[body], into two at the centres of the halves of its
/// cell along that direction. `lower`/`upper` are the held faces of the box (walls, symmetry
/// planes, fixed faces; -inf / +inf where a face is free). `extensive` names the
/// reference-volume-proportional fields (mass, volume0, energies, areas), shared 1/2 : 1/2
/// (axisymmetric: by the half-rings' volumes); `state.fields` are interpolated (split_state.hpp;
/// points whose `failed` field is set keep theirs); `volume` is recomputed as det(F) volume0; every
/// other field is copied (in axisymmetric runs the hoop stretch F_zz becomes each child's r / r0).
/// Near a box face the offset loses its component along the face's normal (a child never crosses a
/// wall, a symmetry plane or the axis); a point whose offset then shrinks below half is not split.
/// The children get ids next_id, next_id + 1, ... (advanced); the parent becomes the first child
/// and the second is appended. Returns the parents in increasing index (the second child of
/// parents[i] is point n + i, n the count before). Serial and in point order: deterministic.
/// Points among which the children's state finds the parents' neighbours: pts's and other ones
/// (other MPI ranks'), in the serial run's order; own_at[p] is pts's point p among them.
struct Neighbourhood {
  FieldStore points;
  std::vector<Index> own_at;
};

/// `neighbourhood`, if given, is where the children's state finds the parents' neighbours; else
/// pts alone.
std::vector<Index> split_points(FieldStore& pts, const std::vector<std::string>& extensive,
                                const std::vector<double>& spacing, int dim, bool axisymmetric, const Vec3& lower,
                                const Vec3& upper, const AdaptivityOptions& opt, const SplitStateSpec& state,
                                const std::string& failed, std::int64_t& next_id,
                                const Neighbourhood* neighbourhood = nullptr);

/// The first child's share of a split point's reference volume, the child at r0 + d0_r: 1/2, or in
/// axisymmetric runs its half-ring's, (r0 + d0_r) / (2 r0) (Pappus: a half-cell's volume per radian
/// is its area times its centroid's radius); the second child's, 1 minus it, sums to 1 exactly.
inline double first_child_share(double r0, double d0_r, bool axisymmetric) {
  return axisymmetric ? 0.5 * (r0 + d0_r) / r0 : 0.5;
}

/// True if two nodes of one body that carry mass are closer than `distance` (z ignored in 2D).
bool nodes_crowded(const NodeCloud& nodes, double distance, int dim);

}  // namespace ballista::otm
