// Only MPI's C API is used (Open MPI's C++ bindings would need their own library).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include "core/communicator.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <mpi.h>

namespace ballista {

namespace {

static_assert(sizeof(MPI_Comm) <= sizeof(std::uintptr_t), "MPI_Comm must fit the opaque handle");

bool g_we_initialised = false;

bool mpi_running() {
  int init = 0, fin = 0;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  return init && !fin;
}

MPI_Comm comm_of(std::uintptr_t h) {
  MPI_Comm c;
  std::memcpy(&c, &h, sizeof(MPI_Comm));
  return c;
}

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI call failed: ") + what);
}

}  // namespace

void Communicator::init_if_launched(int* argc, char*** argv) {
  // Open MPI's launcher sets OMPI_COMM_WORLD_SIZE, MPICH/Hydra and Slurm set PMI_SIZE: a process
  // started without them is a plain serial run and never touches MPI (no singleton start-up).
  const bool launched = std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
  if (!launched || mpi_running()) return;
  int provided = 0;
  check(MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  g_we_initialised = true;
}

void Communicator::finalize() {
  if (g_we_initialised && mpi_running()) MPI_Finalize();
  g_we_initialised = false;
}

Communicator Communicator::world() {
  Communicator c;
  if (!mpi_running()) return c;
  MPI_Comm w = MPI_COMM_WORLD;
  MPI_Comm_rank(w, &c.rank_);
  MPI_Comm_size(w, &c.size_);
  std::uintptr_t h = 0;
  std::memcpy(&h, &w, sizeof(MPI_Comm));
  c.handle_ = h;
  if (c.size_ == 1) c.handle_ = 0;  // one rank: the serial paths
  return c;
}

namespace {
/// One value reduced over every rank.
template <class T>
T all_reduce(T local, MPI_Datatype type, MPI_Op op, std::uintptr_t handle) {
  T global{};
  check(MPI_Allreduce(&local, &global, 1, type, op, comm_of(handle)), "MPI_Allreduce");
  return global;
}
}  // namespace

double Communicator::sum(double local) const {
  return distributed() ? all_reduce(local, MPI_DOUBLE, MPI_SUM, handle_) : local;
}

void Communicator::sum(double* values, int n) const {
  if (!distributed() || n == 0) return;
  check(MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, comm_of(handle_)), "MPI_Allreduce");
}

void Communicator::sum(std::int64_t* values, int n) const {
  if (!distributed() || n == 0) return;
  check(MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_INT64_T, MPI_SUM, comm_of(handle_)), "MPI_Allreduce");
}

double Communicator::min(double local) const {
  return distributed() ? all_reduce(local, MPI_DOUBLE, MPI_MIN, handle_) : local;
}

double Communicator::max(double local) const {
  return distributed() ? all_reduce(local, MPI_DOUBLE, MPI_MAX, handle_) : local;
}

std::int64_t Communicator::sum(std::int64_t local) const {
  return distributed() ? all_reduce(local, MPI_INT64_T, MPI_SUM, handle_) : local;
}

void Communicator::max(std::int64_t* values, int n) const {
  if (!distributed() || n == 0) return;
  check(MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_INT64_T, MPI_MAX, comm_of(handle_)), "MPI_Allreduce");
}

std::int64_t Communicator::max(std::int64_t local) const {
  return distributed() ? all_reduce(local, MPI_INT64_T, MPI_MAX, handle_) : local;
}

bool Communicator::any(bool local) const {
  return distributed() ? all_reduce(local ? 1 : 0, MPI_INT, MPI_LOR, handle_) != 0 : local;
}

int Communicator::lowest_rank_with(bool flag) const {
  if (!distributed()) return flag ? 0 : 1;
  return all_reduce(flag ? rank_ : size_, MPI_INT, MPI_MIN, handle_);
}

int Communicator::rank_of_max(double key) const {
  if (!distributed()) return 0;
  struct {
    double v;
    int r;
  } in{key, rank_}, out{0.0, 0};
  check(MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_of(handle_)), "MPI_Allreduce");
  return out.r;
}

void Communicator::broadcast(void* data, std::size_t bytes, int root) const {
  if (!distributed() || bytes == 0) return;
  check(MPI_Bcast(data, static_cast<int>(bytes), MPI_BYTE, root, comm_of(handle_)), "MPI_Bcast");
}

std::string Communicator::broadcast(const std::string& s, int root) const {
  if (!distributed()) return s;
  std::int64_t n = static_cast<std::int64_t>(s.size());
  broadcast(&n, sizeof n, root);
  std::string out = rank_ == root ? s : std::string(static_cast<std::size_t>(n), '\0');
  broadcast(out.data(), out.size(), root);
  return out;
}

namespace {

/// Every rank's vector, concatenated in rank order (MPI_Allgatherv of `type`).
template <class T>
std::vector<T> gather_to_all(const std::vector<T>& mine, std::vector<int>& counts, MPI_Datatype type, MPI_Comm c,
                             int size) {
  int n = static_cast<int>(mine.size());
  counts.assign(size, 0);
  check(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, c), "MPI_Allgather");
  std::vector<int> displ(size, 0);
  for (int r = 1; r < size; ++r) displ[r] = displ[r - 1] + counts[r - 1];
  std::vector<T> all(static_cast<std::size_t>(displ[size - 1] + counts[size - 1]));
  check(MPI_Allgatherv(mine.data(), n, type, all.data(), counts.data(), displ.data(), type, c), "MPI_Allgatherv");
  return all;
}

}  // namespace

std::vector<std::int64_t> Communicator::all_gather(const std::vector<std::int64_t>& mine,
                                                   std::vector<int>& counts) const {
  if (!distributed()) {
    counts.assign(1, static_cast<int>(mine.size()));
    return mine;
  }
  return gather_to_all(mine, counts, MPI_INT64_T, comm_of(handle_), size_);
}

std::vector<double> Communicator::all_gather_reals(const std::vector<double>& mine, std::vector<int>& counts) const {
  if (!distributed()) {
    counts.assign(1, static_cast<int>(mine.size()));
    return mine;
  }
  return gather_to_all(mine, counts, MPI_DOUBLE, comm_of(handle_), size_);
}

std::vector<std::vector<char>> Communicator::all_to_all(const std::vector<std::vector<char>>& send) const {
  std::vector<std::vector<char>> recv;
  all_to_all(send, recv);
  return recv;
}

void Communicator::all_to_all(const std::vector<std::vector<char>>& send, std::vector<std::vector<char>>& recv) const {
  recv.resize(static_cast<std::size_t>(size_));
  for (auto& r : recv) r.clear();
  if (!distributed()) return;
  const MPI_Comm c = comm_of(handle_);
  // Message sizes first, then the payloads (counts in bytes; a rank's share stays below 2 GiB
  // per peer and step: migration moves the few particles that crossed a cut).
  std::vector<int> scount(size_, 0), rcount(size_, 0);
  for (int r = 0; r < size_; ++r)
    if (r != rank_) scount[r] = static_cast<int>(send[r].size());
  check(MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, c), "MPI_Alltoall");
  std::vector<int> sdispl(size_, 0), rdispl(size_, 0);
  for (int r = 1; r < size_; ++r) {
    sdispl[r] = sdispl[r - 1] + scount[r - 1];
    rdispl[r] = rdispl[r - 1] + rcount[r - 1];
  }
  // The staging buffers keep their pages from call to call (a fresh large allocation costs a page
  // fault per page; the OTM node sums exchange megabytes every step).
  static thread_local std::vector<char> sbuf, rbuf;
  sbuf.resize(static_cast<std::size_t>(sdispl[size_ - 1] + scount[size_ - 1]));
  for (int r = 0; r < size_; ++r)
    if (scount[r] > 0) std::memcpy(sbuf.data() + sdispl[r], send[r].data(), static_cast<std::size_t>(scount[r]));
  rbuf.resize(static_cast<std::size_t>(rdispl[size_ - 1] + rcount[size_ - 1]));
  check(MPI_Alltoallv(sbuf.data(), scount.data(), sdispl.data(), MPI_BYTE, rbuf.data(), rcount.data(),
                      rdispl.data(), MPI_BYTE, c),
        "MPI_Alltoallv");
  for (int r = 0; r < size_; ++r)
    recv[r].assign(rbuf.begin() + rdispl[r], rbuf.begin() + rdispl[r] + rcount[r]);
}

std::vector<std::vector<char>> Communicator::gather(const std::vector<char>& mine, int root) const {
  std::vector<std::vector<char>> out;
  if (!distributed()) {
    out.push_back(mine);
    return out;
  }
  const MPI_Comm c = comm_of(handle_);
  // 64-bit sizes: a gathered output of 10^7 particles is more than 2 GiB; sent in chunks.
  std::int64_t n = static_cast<std::int64_t>(mine.size());
  std::vector<std::int64_t> sizes(rank_ == root ? size_ : 0);
  check(MPI_Gather(&n, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, root, c), "MPI_Gather");
  constexpr std::int64_t kChunk = 1 << 30;
  if (rank_ == root) {
    out.resize(size_);
    for (int r = 0; r < size_; ++r) {
      if (r == root) {
        out[r] = mine;
        continue;
      }
      out[r].resize(static_cast<std::size_t>(sizes[r]));
      for (std::int64_t off = 0; off < sizes[r]; off += kChunk)
        check(MPI_Recv(out[r].data() + off, static_cast<int>(std::min(kChunk, sizes[r] - off)), MPI_BYTE, r, 7, c,
                       MPI_STATUS_IGNORE),
              "MPI_Recv");
    }
  } else {
    for (std::int64_t off = 0; off < n; off += kChunk)
      check(MPI_Send(mine.data() + off, static_cast<int>(std::min(kChunk, n - off)), MPI_BYTE, root, 7, c),
            "MPI_Send");
  }
  return out;
}

void Communicator::exchange(const std::vector<int>& peers, const std::vector<std::vector<double>>& send,
                            std::vector<std::vector<double>>& recv) const {
  if (!distributed() || peers.empty()) return;
  const MPI_Comm c = comm_of(handle_);
  std::vector<MPI_Request> req(2 * peers.size());
  for (std::size_t k = 0; k < peers.size(); ++k) {
    check(MPI_Irecv(recv[k].data(), static_cast<int>(recv[k].size()), MPI_DOUBLE, peers[k], 11, c, &req[2 * k]),
          "MPI_Irecv");
    check(MPI_Isend(send[k].data(), static_cast<int>(send[k].size()), MPI_DOUBLE, peers[k], 11, c,
                    &req[2 * k + 1]),
          "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
}

void Communicator::barrier() const {
  if (distributed()) MPI_Barrier(comm_of(handle_));
}

}  // namespace ballista
