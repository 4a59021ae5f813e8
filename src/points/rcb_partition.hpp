#pragma once
// Which rank owns which points: recursive coordinate bisection (Berger & Bokhari, IEEE Trans.
// Comput. 36 (1987) 570) computed by Zoltan (Boman et al., Sandia; Debian libtrilinos-zoltan-dev),
// weighted by point count, so every rank holds about the same number of points. The cuts are kept
// (KEEP_CUTS), so the owner of any position is known without communication (Zoltan's point
// assignment); a repartition starts from the previous cuts (RCB_REUSE). Solver-neutral: MPM
// particles today, peridynamic and OTM points next (issue 16).
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
  /// The rank whose region holds x (after a partition; no communication).
  int owner(const Vec3& x) const;
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
};

}  // namespace ballista
