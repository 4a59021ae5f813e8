#pragma once
// The points a peridynamic rank computes with (docs/parallel.md). Peridynamics is
// Lagrangian: bonds are made once in the reference configuration and the cost of a point is its
// bond count, so the points are partitioned once, at the start, by recursive coordinate bisection
// of their reference positions (points/rcb_partition.hpp) and never migrate (Peridigm's choice).
// A rank holds its own points (the PointSet's store) and ghost copies of others':
//  - bond ghosts: every point bonded to an own point (fixed for the run);
//  - contact ghosts: every other point within the contact cutoff of an own point when the contact
//    list was last built (found anew at each build from the cells the ranks' points occupy).
// Local numbering: own points and bond ghosts interleaved in increasing id, then the contact
// ghosts. Every own point then has its serial bond row, in the serial order, so the forces,
// breaks and sums of a bond pass over blocks of ids are those of the serial run, bit for bit.
// Each step every rank sends its neighbours their ghosts' positions and critical stretches, one
// message per neighbouring rank (Communicator::exchange).
#include <cstdint>
#include <vector>

#include "core/communicator.hpp"
#include "core/parallel.hpp"
#include "core/tensor.hpp"

namespace ballista::pd {

/// The local points: own ones and ghosts. Static data are copies; x is refreshed every step.
struct LocalPoints {
  std::vector<std::int64_t> id, body, material;
  std::vector<Vec3> x0, x;
  std::vector<double> vol0;
  std::vector<std::uint8_t> ghost;  ///< 1 for a ghost copy
  std::vector<Index> own;           ///< local index of each own point (store order = id order)
  Index bond_local = 0;             ///< own points and bond ghosts; contact ghosts follow

  Index size() const { return static_cast<Index>(id.size()); }
  /// Appends a point (a ghost unless `is_own`).
  void push(std::int64_t id, std::int64_t body, std::int64_t material, const Vec3& x0,
            const Vec3& x, double vol0, bool is_own);
  /// Drops every point from `n` on.
  void truncate(Index n);
};

class PdHalo {
 public:
  /// Collective. The bond ghosts of `local` (ghost[l] set, owner[l] their ranks) are requested from
  /// their owners; afterwards update() refreshes them.
  void plan_bond_ghosts(const Communicator& comm, const LocalPoints& local,
                        const std::vector<int>& owner);
  /// Collective: every ghost gets its owner's x and s0 (bond ghosts) or x (contact ghosts).
  void update(const Communicator& comm, LocalPoints& local, std::vector<double>& s0) const;
  /// Collective: the bond ghosts get their owners' values of a per-point array (setup).
  void update_bond_values(const Communicator& comm, const LocalPoints& local,
                          std::vector<double>& values) const;

  /// Collective, at a contact list build: drops the contact ghosts and appends every other rank's
  /// points in the cells (of edge `cutoff`) around this rank's own points at the current positions
  /// (in the x-y plane when dim is 2) that are not bond ghosts here already: every point within
  /// the cutoff of an own point, and few more. Own points with skip[l] != 0 (vented gas) take no
  /// part.
  void gather_contact_ghosts(const Communicator& comm, LocalPoints& local, double cutoff, int dim,
                             const std::uint8_t* skip = nullptr);
  /// Collective: keeps the contact ghosts with needed[l] != 0 (l from bond_local on; the others are
  /// dropped) and tells their owners; returns each local point's new index (-1: dropped).
  std::vector<Index> keep_contact_ghosts(const Communicator& comm, LocalPoints& local,
                                         const std::vector<char>& needed);

  /// Ranks this rank exchanges ghosts with, and the bytes it sends per update (summary, docs).
  std::vector<int> peers() const;
  std::int64_t bytes_per_update() const;
  /// Bytes this rank offered other ranks at contact list builds so far (the candidates sent
  /// before each receiver keeps the ones in range).
  std::int64_t offered_bytes() const { return offered_bytes_; }
  void set_offered_bytes(std::int64_t b) { offered_bytes_ = b; }  ///< restart

 private:
  int ranks_ = 1;
  // Per rank r: local indices of own points whose values r needs (send) and of ghosts r owns
  // (receive), bond ghosts first, each in the order the receiver asked for them.
  std::vector<std::vector<Index>> bond_send_, bond_recv_, contact_send_, contact_recv_;
  std::vector<std::vector<Index>> bond_sent_;  ///< bond_send_ sorted (is a point a bond ghost there?)
  // At a contact ghost gather: what this rank offered each rank (local indices), and for each
  // received contact ghost its source rank and place in that rank's offer.
  std::vector<std::vector<Index>> offered_;
  std::vector<int> contact_source_;
  std::int64_t offered_bytes_ = 0;
  std::vector<Index> contact_slot_;
};

}  // namespace ballista::pd
