// The stepping thread's scheduling (simulation::StepScheduling): read per
// thread, recorded in summary.json (step_time.scheduling), and a warning
// where a real-time policy meets the kernel's real-time throttling, which
// stalls the step for the rest of each period once the runtime is used up
// (52.6 ms measured: docs/benchmarks.md, "Real-time scheduling for the
// step"). A real-time policy needs privileges a test may not have, so the
// warning is checked on given values; the reading is checked on a thread
// switched to SCHED_BATCH, which needs none (and end to end by
// tests/simulation/test_step_scheduling.sh).
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <string>
#include <thread>

#include "pcsim/simulation/step_scheduling.hpp"

namespace {

using pcsim::simulation::StepScheduling;

StepScheduling given(const char* policy, int priority, long runtime_us, long period_us) {
  StepScheduling s;
  s.policy = policy;
  s.priority = priority;
  s.read = true;
  s.rt_runtime_us = runtime_us;
  s.rt_period_us = period_us;
  return s;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(StepScheduling, WarnsOnlyForARealTimePolicyUnderThrottling) {
  // Linux's default limits: 950000 of 1000000 us.
  const auto fifo = given("fifo", 10, 950000, 1000000);
  EXPECT_TRUE(fifo.throttled());
  const std::string w = fifo.throttle_warning();
  for (const char* part :
       {"SCHED_FIFO (priority 10)", "sched_rt_runtime_us 950000", "sched_rt_period_us 1000000",
        "run 0.95 s of a period", "the 50 ms left of it",
        "echo -1 > /proc/sys/kernel/sched_rt_runtime_us"})
    EXPECT_TRUE(contains(w, part)) << part << " not in: " << w;
  EXPECT_TRUE(
      contains(given("rr", 3, 900000, 1000000).throttle_warning(), "SCHED_RR (priority 3)"));
  EXPECT_TRUE(contains(given("rr", 3, 900000, 1000000).throttle_warning(), "the 100 ms left"));
  // Throttling off (-1), or a runtime of the whole period: no stall.
  EXPECT_EQ(given("fifo", 10, -1, 1000000).throttle_warning(), "");
  EXPECT_EQ(given("fifo", 10, 1000000, 1000000).throttle_warning(), "");
  // Ordinary policies are not throttled; limits not read: no claim.
  for (const char* policy : {"other", "batch", "idle"})
    EXPECT_FALSE(given(policy, 0, 950000, 1000000).throttled()) << policy;
  auto unread = given("fifo", 10, 950000, 1000000);
  unread.read = false;
  EXPECT_FALSE(unread.throttled());
  EXPECT_TRUE(unread.json()["rt_runtime_us"].is_null());
  EXPECT_TRUE(unread.json()["rt_period_us"].is_null());
  EXPECT_EQ(fifo.json()["policy"], "fifo");
  EXPECT_EQ(fifo.json()["priority"], 10);
  EXPECT_EQ(fifo.json()["rt_runtime_us"], 950000);
}

TEST(StepScheduling, ReadsTheCallingThreadsPolicy) {
  const auto here = StepScheduling::of_this_thread();
  const int policy = sched_getscheduler(0);
  const char* expected = policy == SCHED_BATCH  ? "batch"
                         : policy == SCHED_IDLE ? "idle"
                         : policy == SCHED_FIFO ? "fifo"
                         : policy == SCHED_RR   ? "rr"
                                                : "other";
  EXPECT_EQ(here.policy, expected);
  StepScheduling there;
  std::thread batch([&there] {
    sched_param param{};
    ASSERT_EQ(pthread_setschedparam(pthread_self(), SCHED_BATCH, &param), 0);
    there = StepScheduling::of_this_thread();
  });
  batch.join();
  EXPECT_EQ(there.policy, "batch");
  EXPECT_EQ(there.priority, 0);
  // This thread kept its own.
  EXPECT_EQ(StepScheduling::of_this_thread().policy, here.policy);
  // The kernel's limits where /proc has them (Linux): a period and a
  // runtime of -1 (off) or within it.
  if (there.read) {
    EXPECT_GT(there.rt_period_us, 0);
    EXPECT_TRUE(there.rt_runtime_us == -1 ||
                (there.rt_runtime_us >= 0 && there.rt_runtime_us <= there.rt_period_us));
  }
}

}  // namespace
