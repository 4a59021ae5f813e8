#pragma once
// A failure seen by one rank stops every rank with the same diagnostic: a solver step
// catches what its rank threw, then all ranks agree here. Of the ranks with a particle's failure
// (ParticleError: it names the particle) the one naming the lowest particle id wins, else the
// lowest rank with any failure;
// its message (and particle id) is sent to every rank and thrown there. With one rank this
// rethrows the local failure unchanged.
#include <exception>

#include "core/communicator.hpp"

namespace ballista {

/// Collective. Returns if no rank failed; otherwise throws on every rank.
void rethrow_agreed(const Communicator& comm, std::exception_ptr local);

/// Runs `body` (a solver's step on this rank), then agrees on a failure as above. Nothing in
/// `body` after the first place a rank can throw may wait for the other ranks, so that the ranks
/// that did not fail reach the agreement too.
template <class Body>
void run_agreed(const Communicator& comm, Body&& body) {
  std::exception_ptr failure;
  try {
    body();
  } catch (const std::exception&) {
    failure = std::current_exception();
  }
  rethrow_agreed(comm, failure);
}

}  // namespace ballista
