#pragma once
// The material state a split point's two children start from (seed 003 ch. 5: "it is necessary to
// interpolate internal state variables to new material points ... to ensure they stay in their
// proper manifolds", after Mota et al., Comput. Mech. 52 (2013) 1281).
//
// A child sits a distance d from its parent's centre, so its state is the parent's plus the change
// of a linear reconstruction over d:
//  * the reconstruction is the weighted least-squares gradient over the parent's neighbours of the
//    same body and material (weights 1/r^2, the finite-volume practice; Barth & Jespersen, AIAA
//    89-0366), of each continuous state field: the stress and the models' internal variables;
//  * the two children's changes are weighted so that the parent's share-weighted sums are kept
//    exactly: child a (share w_a) takes +2 w_b G.d and child b takes -2 w_a G.d, so mass times
//    plastic strain and mass times stress are conserved;
//  * a limiter keeps every child's value within the range of the parent's and its neighbours'
//    (no new extrema: damage stays in [0, 1], plastic strain >= 0), with one factor for all the
//    material state of a point, so that a child's state is the same fraction of one
//    reconstruction in every field (stress and hardening move together; for a convex yield
//    surface whose radius is concave in the plastic strain, a state between two admissible ones).
// F is not interpolated: each child's cell is one half of the parent's deformed cell, which F_p
// maps exactly; an F from the neighbours would no longer map the child's own cell (its extent
// tensor, reference box and reference offset), and on the 750 m/s Taylor bar it halved the splits
// (docs/validation.md, OTM). A parent with too few neighbours for a gradient (fewer than dim + 1, or
// all on a line) passes its state on unchanged, as do the fields of discrete values (failure flags,
// counters), which the caller leaves out; failed points are not split (otm_adaptivity.hpp) and take
// no part in a neighbour's gradient.
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/tensor.hpp"

namespace ballista::otm {

/// What the children of a split inherit besides the shared extensive fields and F.
struct SplitStateSpec {
  bool interpolate = true;          ///< false: both children copy the parent's state
  std::vector<std::string> fields;  ///< continuous real fields to interpolate (stress, internal variables)
};

/// One parent's limited changes along its offset d (the first child's side): per component of
/// spec.fields, in order, G . d; empty if the parent passes its state on unchanged.
using SplitIncrement = std::vector<double>;

/// The increments of every parent (before the split moves anything): parents[i] splits into
/// x + offsets[i] and x - offsets[i] (reference offsets ref_offsets[i]; the first child's share
/// 1/2, or in axisymmetric runs its half-ring's). Neighbours of the same body and material (and not
/// failed, if `failed` names a field) within 1.5 times the parent's extent (its cell's longest
/// edge, the extent tensor of otm_adaptivity.hpp) count: those on both sides along the split
/// direction, whose cells have stretched too.
std::vector<SplitIncrement> split_increments(const FieldStore& pts, const std::vector<Index>& parents,
                                             const std::vector<Vec3>& offsets, const std::vector<Vec3>& ref_offsets,
                                             bool axisymmetric, const SplitStateSpec& spec, int dim,
                                             const std::string& failed);

/// Applies the increments to the children, which both hold their parent's state: parents[i]
/// itself (at +d, share shares[2 i]) and point first_new + i (at -d).
void apply_split_increments(FieldStore& pts, const std::vector<SplitIncrement>& increments,
                            const std::vector<Index>& parents, Index first_new, const std::vector<double>& shares,
                            const SplitStateSpec& spec);

}  // namespace ballista::otm
