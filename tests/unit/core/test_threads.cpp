// Thread-count requests (core/threads.hpp): clamped to the cores present, 0 = the default.
#include <gtest/gtest.h>

#include "core/parallel.hpp"
#include "core/threads.hpp"

namespace test_threads {

using namespace ballista;

TEST(Threads, ClampThreadCountLimitsRequestsToTheCores) {
  EXPECT_EQ(clamp_thread_count(100000, 2), 2);
  EXPECT_EQ(clamp_thread_count(3, 2), 2);
  EXPECT_EQ(clamp_thread_count(2, 2), 2);
  EXPECT_EQ(clamp_thread_count(1, 2), 1);
  EXPECT_EQ(clamp_thread_count(5, 64), 5);
  EXPECT_EQ(clamp_thread_count(2147483647, 1), 1);
  EXPECT_EQ(clamp_thread_count(4, 0), 1);  // no core count known: one thread, never zero
}

TEST(Threads, ClampThreadCountKeepsNonPositiveRequests) {
  EXPECT_EQ(clamp_thread_count(0, 2), 0);  // 0 = the default (all cores)
  EXPECT_EQ(clamp_thread_count(-3, 2), -3);
}

TEST(Threads, AvailableCoresIsAtLeastOne) { EXPECT_GE(available_cores(), 1); }

#ifdef _OPENMP
TEST(Threads, RequestThreadsAppliesTheClampedCount) {
  const int saved = max_threads();
  const int cores = available_cores();
  EXPECT_EQ(request_threads(100000, "--threads"), cores);
  EXPECT_EQ(max_threads(), cores);
  EXPECT_EQ(request_threads(1, "--threads"), 1);
  EXPECT_EQ(request_threads(0, "simulation.threads"), 1);  // 0 leaves the count as it is
  EXPECT_EQ(request_threads(cores + 1, "simulation.threads"), cores);
  set_threads(saved);
}
#endif

}  // namespace test_threads
