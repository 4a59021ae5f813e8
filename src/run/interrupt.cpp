#include "run/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace ballista {

namespace {

std::atomic<int> g_requested{0};  // lock-free: the only thing the handler touches; 1 signal, 2 caller

extern "C" void on_signal(int sig) {
  if (g_requested.exchange(1) != 0 && sig == SIGINT) {
    // A second Ctrl-C: the user insists. Default action (terminate) without the checkpoint.
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
  // A second SIGTERM is not insistence but a copy: a batch system signals every task of the job,
  // and mpirun passes the one it got on odls_base_sigkill_timeout seconds later. Ending the rank
  // then would cut its checkpoint short; the scheduler's SIGKILL follows anyway if it lasts.
  // (glibc's std::signal keeps the handler installed after a call, so the copy lands here too.)
}

}  // namespace

InterruptScope::InterruptScope() {
  term_ = std::signal(SIGTERM, on_signal);
  int_ = std::signal(SIGINT, on_signal);
}

InterruptScope::~InterruptScope() {
  std::signal(SIGTERM, term_ == SIG_ERR ? SIG_DFL : term_);
  std::signal(SIGINT, int_ == SIG_ERR ? SIG_DFL : int_);
}

bool interrupt_requested() { return g_requested.load() != 0; }
void request_interrupt() {
  int none = 0;
  g_requested.compare_exchange_strong(none, 2);
}
bool interrupt_from_caller() { return g_requested.load() == 2; }
void clear_interrupt() { g_requested.store(0); }

}  // namespace ballista
