#include "core/agreed_failure.hpp"

#include <cstdint>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace ballista {

void rethrow_agreed(const Communicator& comm, std::exception_ptr local) {
  if (!comm.distributed()) {
    if (local) std::rethrow_exception(local);
    return;
  }
  // 2: a particle's failure, 1: another physics failure, 0: none (a programming error is a
  // physics failure here too: the other ranks must not wait for this one forever).
  int kind = 0;
  std::string message;
  std::int64_t id = -1;
  if (local) {
    try {
      std::rethrow_exception(local);
    } catch (const ParticleError& e) {
      kind = 2;
      message = e.what();
      id = e.id();
    } catch (const std::exception& e) {
      kind = 1;
      message = e.what();
    }
  }
  if (!comm.any(kind > 0)) return;
  int root = comm.size();
  if (comm.any(kind == 2)) {
    // The lowest particle id among the ranks' failures: each rank reports the first failing point
    // of its own order, so with points in id order (peridynamics) this is the serial run's choice.
    const std::int64_t lowest = -comm.max(kind == 2 ? -id : std::numeric_limits<std::int64_t>::min());
    root = comm.lowest_rank_with(kind == 2 && id == lowest);
  } else {
    root = comm.lowest_rank_with(kind == 1);
  }
  message = comm.broadcast(message, root);
  comm.broadcast(&id, sizeof id, root);
  if (id >= 0) throw ParticleError(id, message);
  throw PhysicsError(message + (comm.rank() == root ? "" : " (rank " + std::to_string(root) + ")"));
}

}  // namespace ballista
