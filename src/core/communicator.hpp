#pragma once
// The one place every global reduction and every message between ranks goes through (energies,
// time step, probes, counts, particle migration, grid halos). A default-constructed Communicator
// is a single process and calls no MPI; Communicator::world() is MPI_COMM_WORLD once the program
// has initialised MPI (apps/ballista.cpp, when launched by mpirun), otherwise the same single
// process. mpi.h stays in communicator.cpp: the MPI_Comm handle is kept as an opaque word.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ballista {

class Communicator {
 public:
  /// A single process (no MPI calls).
  Communicator() = default;
  /// MPI_COMM_WORLD if MPI is initialised, else a single process.
  static Communicator world();
  /// Initialises MPI with MPI_THREAD_FUNNELED (OpenMP threads inside a rank, MPI from the master
  /// thread) when the process was launched by mpirun/mpiexec; nothing otherwise. Idempotent.
  static void init_if_launched(int* argc, char*** argv);
  /// MPI_Finalize if init_if_launched started MPI.
  static void finalize();

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// More than one rank: the MPI paths are taken.
  bool distributed() const { return size_ > 1; }

  // ---- reductions (every rank gets the result) ------------------------------------------------
  double sum(double local) const;
  /// Element-wise sum of n values in place.
  void sum(double* values, int n) const;
  void sum(std::int64_t* values, int n) const;
  /// Element-wise maximum of n values in place.
  void max(std::int64_t* values, int n) const;
  double min(double local) const;
  double max(double local) const;
  std::int64_t sum(std::int64_t local) const;
  std::int64_t max(std::int64_t local) const;
  bool any(bool local) const;
  /// The lowest rank whose flag is set, or size() if none.
  int lowest_rank_with(bool flag) const;
  /// The rank holding the largest key (the lowest such rank on ties).
  int rank_of_max(double key) const;

  // ---- collectives on bytes --------------------------------------------------------------------
  void broadcast(void* data, std::size_t bytes, int root) const;
  std::string broadcast(const std::string& s, int root) const;
  /// Every rank's vector, concatenated in rank order; counts[r] = rank r's length.
  std::vector<std::int64_t> all_gather(const std::vector<std::int64_t>& mine, std::vector<int>& counts) const;
  std::vector<double> all_gather_reals(const std::vector<double>& mine, std::vector<int>& counts) const;
  /// send[r]: bytes for rank r (send[rank()] is ignored); returns what each rank sent here.
  std::vector<std::vector<char>> all_to_all(const std::vector<std::vector<char>>& send) const;
  /// The same into recv, whose vectors keep their capacity (a caller exchanging every step).
  void all_to_all(const std::vector<std::vector<char>>& send, std::vector<std::vector<char>>& recv) const;
  /// Everything to `root` (rank order); other ranks get an empty result.
  std::vector<std::vector<char>> gather(const std::vector<char>& mine, int root) const;
  /// Point-to-point with known sizes: sends send[k] to peers[k] and receives recv[k] (already
  /// sized) from peers[k], all at once (non-blocking, then wait).
  void exchange(const std::vector<int>& peers, const std::vector<std::vector<double>>& send,
                std::vector<std::vector<double>>& recv) const;
  void barrier() const;
  /// The MPI_Comm as an opaque word, for libraries that take one (Zoltan: points/rcb_partition).
  std::uintptr_t native_handle() const { return handle_; }

 private:
  int rank_ = 0;
  int size_ = 1;
  std::uintptr_t handle_ = 0;  ///< the MPI_Comm (distributed only)
};

}  // namespace ballista
