#pragma once
// Short-range contact between peridynamic points that were never bonded: points of different
// bodies, and points of one body farther apart than the horizon in the reference configuration
// (a body folding onto itself). Pairs whose bond broke are handled in the bond loop itself (their
// bond row already holds them), so bond failures never invalidate this list.
//
// Contact law (Silling & Askari, Comput. Struct. 83 (2005) 1526, §"short-range forces"; LAMMPS
// PERI pair_peri_pmb): a pair closer than d = min(0.9 |xi|, 1.35 dx) repels with the force density
// c_s (d - |y|)/delta per unit volume squared, c_s = 15 c (c the bond micromodulus). For pairs of
// different bodies |xi| is their distance in the reference configuration (so d = 1.35 dx for
// bodies that start apart).
//
// The list holds every never-bonded pair within 1.35 dx + skin in the configuration of its last
// build (cell binning, O(N)); it is rebuilt when some point has moved more than skin/2 since,
// so no pair can come within 1.35 dx unseen (each end moved < skin/2).
#include <cstdint>
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"

namespace ballista::pd {

struct ContactList {
  std::vector<Index> offset;        ///< row start of each point (size n + 1; both ends hold the pair)
  std::vector<std::int32_t> other;  ///< the other point
  std::vector<double> reach;        ///< d = min(0.9 |xi|, 1.35 dx), m
  std::vector<Vec3> x_build;        ///< positions at the last build
  double skin = 0.0;                ///< m
  long builds = 0;                  ///< number of builds so far

  Index pairs() const { return other.empty() ? 0 : static_cast<Index>(other.size()) / 2; }
  /// True if some point (skip[p] == 0) moved more than skin/2 since the last build (or there was none).
  bool stale(const Vec3* x, Index n, const std::uint8_t* skip = nullptr) const;
};

/// Builds the list of never-bonded pairs (different `body`, or reference distance > delta) within
/// 1.35 dx + skin of each other at the positions x (x0: reference positions). Points with
/// skip[p] != 0 (vented gas) take no part; two points with gas != 0 (detonation products) are
/// never a pair: the gas has no contact stiffness of its own, only the solids it meets. Rows are
/// in increasing `key` of the other point (the global id on several ranks, whose ghosts are not in
/// id order; null: the index), so the force sums run in the serial run's order.
void build_contact_list(ContactList& list, const Vec3* x, const Vec3* x0, const std::int64_t* body, Index n,
                        double delta, double dx, double skin, int dim, const std::uint8_t* skip = nullptr,
                        const std::uint8_t* gas = nullptr, const std::int64_t* key = nullptr);

}  // namespace ballista::pd
