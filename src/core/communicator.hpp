#pragma once
// The one place every global reduction goes through (energies, time step, probes, counts).
// Today a single process; the MPI build replaces the bodies with MPI_Allreduce over the
// rank-owned grid blocks without touching any caller.
#include <algorithm>
#include <cstdint>

namespace ballista {

class Communicator {
 public:
  int rank() const { return 0; }
  int size() const { return 1; }
  double sum(double local) const { return local; }
  void sum(double* values, int n) const { (void)values; (void)n; }
  double min(double local) const { return local; }
  double max(double local) const { return local; }
  std::int64_t sum(std::int64_t local) const { return local; }
  bool any(bool local) const { return local; }
};

}  // namespace ballista
