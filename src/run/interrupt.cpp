#include "run/interrupt.hpp"

#include <atomic>
#include <csignal>

namespace ballista {

namespace {

std::atomic<int> g_requested{0};  // lock-free: the only thing the handler touches; 1 signal, 2 caller

extern "C" void on_signal(int sig) {
  if (g_requested.exchange(1) != 0) {
    // A second signal: the user insists. Default action (terminate) without the checkpoint.
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
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
