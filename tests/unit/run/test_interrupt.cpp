// The signal handlers of a run (run/interrupt.hpp): the first SIGTERM or SIGINT only asks the run
// loop to checkpoint and stop; a second SIGINT ends the process (Ctrl-C twice: the user insists);
// a second SIGTERM does not (a batch system signals every rank and mpirun passes its own copy on,
// which must not cut the checkpoint short).
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

#include "run/interrupt.hpp"

namespace test_interrupt {

using namespace ballista;

namespace {

void raise_twice_and_exit(int sig) {
  clear_interrupt();
  const InterruptScope scope;
  std::raise(sig);
  if (!interrupt_requested()) std::_Exit(2);  // the first signal must be a request only
  std::raise(sig);
  std::_Exit(interrupt_requested() && !interrupt_from_caller() ? 0 : 3);
}

}  // namespace

TEST(Interrupt, FirstSignalOnlyAsksTheLoopToStop) {
  clear_interrupt();
  {
    const InterruptScope scope;
    std::raise(SIGTERM);
    EXPECT_TRUE(interrupt_requested());
    EXPECT_FALSE(interrupt_from_caller());
  }
  clear_interrupt();
  EXPECT_FALSE(interrupt_requested());
}

TEST(Interrupt, SecondSigtermIsIgnored) {
  EXPECT_EXIT(raise_twice_and_exit(SIGTERM), testing::ExitedWithCode(0), "");
}

TEST(Interrupt, SecondSigintEndsTheProcess) {
  EXPECT_EXIT(raise_twice_and_exit(SIGINT), testing::KilledBySignal(SIGINT), "");
}

TEST(Interrupt, HandlersAreRestoredAfterTheSteps) {
  // Outside the scope SIGTERM acts as without Ballista: it ends the process.
  EXPECT_EXIT({ clear_interrupt(); { const InterruptScope scope; } std::raise(SIGTERM); std::_Exit(0); },
              testing::KilledBySignal(SIGTERM), "");
}

TEST(Interrupt, ACallersRequestIsNotASignal) {
  clear_interrupt();
  request_interrupt();
  EXPECT_TRUE(interrupt_requested());
  EXPECT_TRUE(interrupt_from_caller());
  clear_interrupt();
}

}  // namespace test_interrupt
