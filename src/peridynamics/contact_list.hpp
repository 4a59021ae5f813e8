#pragma once
// Short-range contact between peridynamic points that were never bonded: points of different
// bodies, and points of one body farther apart than the horizon in the reference configuration
// (a body folding onto itself). Pairs whose bond broke are handled in the bond loop itself (their
// bond row already holds them), so bond failures never invalidate this list.
//
// Contact law (Silling & Askari, Comput. Struct. 83 (2005) 1526, §"short-range forces"; LAMMPS
// PERI pair_peri_pmb): a pair closer than d = min(0.9 |xi|, 1.35 dx) (a coarser gas lattice: the
// pair's mean spacing instead of dx) repels with the force density
// c_s (d - |y|)/delta per unit volume squared, c_s = 15 c (c the bond micromodulus). For pairs of
// different bodies |xi| is their distance in the reference configuration (so d = 1.35 dx for
// bodies that start apart).
//
// The list holds every never-bonded pair within 1.35 dx + skin in the configuration of its last
// build (cell binning, O(N)); it is rebuilt before a pair can come within 1.35 dx unseen, i.e.
// when the displacements since the build of its two ends could sum to more than their distance at
// the build minus 1.35 dx (Verlet's neighbour list, with the skin test of e.g. Allen & Tildesley,
// Computer Simulation of Liquids, 2nd ed., §5.3.2, split by kind of point):
//   - solid-solid pairs: every unlisted pair was more than 1.35 dx + skin apart, so the list is
//     good while the solid that moved farthest moved at most skin/2 (m_s <= skin/2);
//   - gas-solid pairs (gas-gas pairs do not exist): a gas point g and any solid were at least
//     a_g + 1.35 dx apart at the build, a_g its allowance (skin, or for gas far from every solid
//     its clearance to them, from the chessboard distance of its bin to the solids' bins), so the
//     list is good while |dx_g| + m_s <= a_g.
// On one rank a list the classic test calls stale is kept if the test on relative motion passes
// (stale_relative: no two points now in neighbouring bins moved by more than the skin relative to
// each other), which the expanding case of an exploding munition needs.
// Without gas this is the classic test (every point within skin/2). A charge's gas far inside the
// case no longer forces a rebuild every step, and the gas next to it has the whole skin less the
// solids' motion; the forces are those of any other list holding every pair within reach, in the
// same order, so fewer rebuilds do not change the answer.
#include <cstdint>
#include <utility>
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "peridynamics/chunked_rows.hpp"

namespace ballista::pd {

struct ContactList {
  std::vector<Index> offset;        ///< row start of each point (size n + 1; both ends hold the pair)
  std::vector<std::int32_t> other;  ///< the other point
  std::vector<double> reach;        ///< d = min(0.9 |xi|, 1.35 dx), m
  std::vector<Vec3> x_build;        ///< positions at the last build
  std::vector<double> allowance;    ///< gas points' a_g (above), m; empty without gas
  double skin = 0.0;                ///< m
  double max_reach = 0.0;           ///< the largest contact distance a pair can have, m (1.35 dx, more with coarse gas)
  long builds = 0;                  ///< number of builds so far
  ChunkedRows scratch;              ///< the search's per-chunk buffers, kept between builds (no new pages)
  std::vector<Index> fill;          ///< the rows' fill positions, kept between builds
  std::vector<std::pair<std::int32_t, double>> entries;  ///< the rows before the split into other and reach
  /// A solid as the search reads it, stored in bin order so that a bin's solids are contiguous.
  struct PackedSolid {
    Vec3 x, x0;
    std::int64_t body;
    Index id;
  };
  std::vector<PackedSolid> packed;  ///< the search's solids in bin order, kept between builds
  std::vector<Vec3> packed_x;       ///< their positions, binned

  Index pairs() const { return other.empty() ? 0 : static_cast<Index>(other.size()) / 2; }
  /// The largest displacement since the last build among the points with skip[p] == 0 that are
  /// not gas (gas null: all of them), m.
  double solid_moved(const Vec3* x, Index n, const std::uint8_t* skip = nullptr,
                     const std::uint8_t* gas = nullptr) const;
  /// True if a pair could have come within reach unseen since the last build (or there was none):
  /// 2 m_s > skin, or some gas point (skip == 0) has |dx_g| + m_s > a_g. `moved_solid` is m_s over
  /// every point that can pair with this rank's (on several ranks, the maximum over the ranks).
  bool stale(const Vec3* x, Index n, double moved_solid, const std::uint8_t* skip = nullptr,
             const std::uint8_t* gas = nullptr) const;
  /// The test on relative motion (every point present, i.e. one rank): true if two points now in
  /// neighbouring bins of size max_reach (gas-gas aside) may have moved by more than the skin
  /// relative to each other since the build. Any pair now within reach sits in neighbouring bins,
  /// and an unlisted one was more than its reach plus the skin apart at the build, so while this
  /// is false the list holds every pair within reach. The bound on two bins' relative motion is
  /// the diagonal of the box spanning both bins' displacements (per kind of point). A case
  /// expanding as a whole moves every point far but brings no two closer: the classic test
  /// rebuilds it every few steps, this one only where pieces fly past each other.
  bool stale_relative(const Vec3* x, Index n, int dim, const std::uint8_t* skip = nullptr,
                      const std::uint8_t* gas = nullptr) const;

  /// stale_relative's buffers, kept between steps.
  struct RelativeScratch {
    std::vector<Vec3> x;
    std::vector<Index> id;
    std::vector<double> box;  ///< per bin: solid lo[3], hi[3], gas lo[3], hi[3]
  };
  mutable RelativeScratch relative;
};

/// Builds the list of never-bonded pairs (different `body`, or reference distance > delta) within
/// 1.35 dx + skin of each other at the positions x (x0: reference positions). Points with
/// skip[p] != 0 (vented gas) take no part; two points with gas != 0 (detonation products) are
/// never a pair: the gas has no contact stiffness of its own, only the solids it meets. Rows are
/// in increasing `key` of the other point (the global id on several ranks, whose ghosts are not in
/// id order; null: the index), so the force sums run in the serial run's order. `clearance`:
/// give gas far from every solid its clearance as allowance (only where every solid that could
/// come near is present, i.e. on one rank); otherwise each gas point's allowance is the skin.
/// `scale` (per point, nullptr: all 1): gas seeded on a lattice scale times coarser than dx (a
/// body's point_spacing); a pair's 1.35 dx becomes 1.35 dx (a_p + a_q)/2, a solid's a being 1.
void build_contact_list(ContactList& list, const Vec3* x, const Vec3* x0, const std::int64_t* body, Index n,
                        double delta, double dx, double skin, int dim, const std::uint8_t* skip = nullptr,
                        const std::uint8_t* gas = nullptr, const std::int64_t* key = nullptr,
                        bool clearance = false, const double* scale = nullptr);

}  // namespace ballista::pd
