#pragma once
// Which rank owns which points: recursive coordinate bisection (Berger & Bokhari, IEEE Trans.
// Comput. 36 (1987) 570) computed by Zoltan (Boman et al., Sandia; Debian libtrilinos-zoltan-dev),
// weighted by point count, so every rank holds about the same number of points. The cuts are kept
// (KEEP_CUTS) as every rank's region box, so the owner of any position is known without
// communication, and a checkpoint can store them. A repartition depends only on where the points
// are (no RCB_REUSE), so a restarted run cuts where the uninterrupted one did. Solver-neutral: it
// sees points, not particles, so MPM and peridynamics partition with the same code.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/communicator.hpp"
#include "core/parallel.hpp"
#include "core/tensor.hpp"

namespace ballista {

class RcbPartition {
 public:
  /// `dim` coordinates of each point take part (2 in plane strain and axisymmetric runs).
  RcbPartition(const Communicator& comm, int dim);
  ~RcbPartition();
  RcbPartition(const RcbPartition&) = delete;
  RcbPartition& operator=(const RcbPartition&) = delete;

  /// Computes the cuts from the points every rank holds now (collective); the result is the rank
  /// each local point should go to.
  std::vector<int> partition(const Vec3* x, const std::int64_t* ids, Index n);
  /// The rank whose region holds x (after a partition; no communication): the first region box
  /// that holds it, this rank's own box tried first.
  int owner(const Vec3& x) const;
  /// The region boxes of every rank (lower then upper corner, 6 values per rank), for a
  /// checkpoint; restore_boxes() makes owner() answer as it did then.
  const std::vector<double>& boxes() const { return boxes_; }
  void restore_boxes(const std::vector<double>& boxes);
  /// The ranks whose region, grown by `margin` on every side, overlaps this rank's grown by as
  /// much (a symmetric relation; after a partition).
  std::vector<int> neighbours(double margin) const;
  /// Owners of n points (no communication).
  void owners(const Vec3* x, Index n, std::vector<int>& out) const;
  bool ready() const { return ready_; }
  int partitions() const { return partitions_; }

  struct Impl;  ///< Zoltan's handle and the points of a partition call (its callbacks read them)

 private:
  std::unique_ptr<Impl> impl_;
  Communicator comm_;
  int dim_;
  bool ready_ = false;
  int partitions_ = 0;
  std::vector<double> boxes_;  ///< per rank: xmin ymin zmin xmax ymax zmax of its region
};

}  // namespace ballista
